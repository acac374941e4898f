"""Run by ParaView's own Python (pvbatch): open a siloscope VTU export as ParaView opens it (the .pvd), render its
last frame to PNG, and print what each block holds, one line per block:
    BLOCK name cells=N points=M celltypes=... arrays=a,b,c
    pvbatch render_export.py TRAJECTORY.pvd OUT.png"""
import sys

from paraview import servermanager
import os
import xml.etree.ElementTree as ET

from paraview.simple import ColorBy, CreateView, PVDReader, Render, ResetCamera, SaveScreenshot, Show, \
    XMLUnstructuredGridReader

pvd, out = sys.argv[1], sys.argv[2]
reader = PVDReader(FileName=pvd)
times = list(reader.TimestepValues) if hasattr(reader.TimestepValues, "__len__") else [reader.TimestepValues]
last = times[-1]
reader.UpdatePipeline(time=last)
view = CreateView("RenderView")
view.ViewSize = [800, 800]
view.Background = [1, 1, 1]
try:
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
view.OrientationAxesVisibility = 0
view.ViewTime = last
shown = Show(reader, view)
shown.Representation = "Surface"
ColorBy(shown, ("CELLS", "force"))  # polygon grains and force chains by their force, N
# A run of disks: the grains' centres drawn as disks of their own radius (Point Gaussian scaled by `radius`), what
# a user does in ParaView; a polygon run's shapes block already shows the shapes.
sets = list(ET.parse(pvd).getroot().iter("DataSet"))
if not any(d.get("part") == "2" for d in sets):
    files = [d for d in sets if d.get("part") == "0"]
    grains = XMLUnstructuredGridReader(FileName=[os.path.join(os.path.dirname(pvd), files[-1].get("file"))])
    disks = Show(grains, view)
    disks.SetRepresentationType("Point Gaussian")
    disks.ScaleByArray = 1
    disks.SetScaleArray = ["POINTS", "radius"]
    disks.UseScaleFunction = 0
    disks.GaussianRadius = 1.0
    disks.ShaderPreset = "Plain circle"
    ColorBy(disks, ("POINTS", "species"))
view.CameraPosition = [0, 1, 10]
view.CameraFocalPoint = [0, 1, 0]
view.CameraViewUp = [0, 1, 0]
ResetCamera(view)
Render(view)
SaveScreenshot(out, view, ImageResolution=[800, 800])

data = servermanager.Fetch(reader)
it = data.NewIterator()
it.InitTraversal()
while not it.IsDoneWithTraversal():
    block = it.GetCurrentDataObject()
    name = it.GetCurrentMetaData().Get(data.NAME()) if it.GetCurrentMetaData() else "?"
    arrays = [block.GetPointData().GetArrayName(i) for i in range(block.GetPointData().GetNumberOfArrays())]
    arrays += [block.GetCellData().GetArrayName(i) for i in range(block.GetCellData().GetNumberOfArrays())]
    types = sorted({block.GetCellType(i) for i in range(block.GetNumberOfCells())})
    print(f"BLOCK {name} cells={block.GetNumberOfCells()} points={block.GetNumberOfPoints()} "
          f"celltypes={','.join(map(str, types))} arrays={','.join(arrays)}")
    it.GoToNextItem()
print(f"TIME {last}")
