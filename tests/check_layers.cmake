# Fails if a layer includes what it must not know (see README, "Conventions"):
#   sim knows no GL, ImGui, FFmpeg or stb; render knows no Box2D; record knows no GL or Box2D; core knows none.
#   ui knows render and core only: the app owns the live simulation, reads the trajectory and writes the files
#   (ui/sources.h).
function(forbid dir pattern what)
  file(GLOB_RECURSE files ${SRC}/${dir}/*.h ${SRC}/${dir}/*.cpp)
  foreach(f ${files})
    file(STRINGS ${f} hits REGEX "#include *[<\"](${pattern})")
    if(hits)
      message(SEND_ERROR "${f} includes ${what}: ${hits}")
    endif()
  endforeach()
endfunction()
forbid(sim "GL/|glad|imgui|libav|libsw|stb_|render/|record/" "GL, ImGui, FFmpeg or stb")
forbid(core "box2d|GL/|glad|imgui|libav|libsw|stb_|sim/|render/|record/" "a library or an upper layer")
forbid(render "box2d|sim/|libav|libsw|record/" "Box2D, the simulation or the recorder")
forbid(record "box2d|GL/|glad|imgui|sim/|render/" "GL, Box2D or the simulation")
forbid(analysis "box2d|GL/|glad|imgui|libav|sim/|render/|record/" "a library or an upper layer")
forbid(app "box2d" "Box2D (it stays inside sim)")
# Inside app: commands use services, never the other way round.
forbid(app/services "app/commands" "a command (services serve the commands, not the other way)")
# lab reads positions: the clog rules of core/clog.h and nothing of Box2D, GL or the pictures.
forbid(lab "box2d|GL/|glad|imgui|libav|libsw|stb_|sim/|render/|record/|ui/" "the simulation, Box2D, GL or the pictures")
# vision sees pictures only: OpenCV and core, nothing of the simulation, the renderer or the files.
forbid(vision "box2d|GL/|glad|imgui|libsw|stb_|sim/|render/|record/|ui/|io/|lab/" "an upper layer or Box2D")
forbid(io "box2d|sim/|render/|record/" "Box2D or an upper layer")
forbid(ui "box2d|sim/|analysis/|io/|record/|libav|libsw|stb_"
       "Box2D, the simulation, the analysis or a file format (the app feeds it frames and takes its images)")
file(GLOB_RECURSE osmesa_users ${SRC}/*.cpp ${SRC}/*.h)
foreach(f ${osmesa_users})
  file(STRINGS ${f} hits REGEX "#include *<GL/osmesa.h>")
  if(hits AND NOT f MATCHES "context_osmesa.cpp$")
    message(SEND_ERROR "${f} includes GL/osmesa.h; only src/render/context_osmesa.cpp may")
  endif()
endforeach()
# OpenCV stays with the pictures of a camera: vision/, and the service that feeds it frames (app/services/lab).
foreach(f ${osmesa_users})
  file(STRINGS ${f} hits REGEX "#include *<opencv2/")
  if(hits AND NOT f MATCHES "/src/vision/" AND NOT f MATCHES "/src/app/services/lab\\.(cpp|h)$")
    message(SEND_ERROR "${f} includes OpenCV; only src/vision/ and src/app/services/lab may")
  endif()
endforeach()
