#include "app/services/inspect_files.h"
#include <toml++/toml.h>
#include <unistd.h>
#include "app/services/process.h"
#include "core/error.h"
#include "core/format.h"
#include "io/metadata.h"
#include "io/output.h"

#include "record/mp4.h"
#include "record/png.h"

namespace app {

void title_imported(ui::Inspector& insp, const io::Run& run) {
  if (!run.imported()) return;
  toml::table t;
  try {
    t = toml::parse(run.metadata_text());
  } catch (const toml::parse_error&) {
    return;
  }
  insp.overlay_data.title =
      "imported: " +
      std::filesystem::path(t["run"]["imported_from"].value_or(std::string())).filename().string() +
      " (contacts: gap <= " + core::format_g(t["run"]["contact_tolerance"].value_or(0.0), 3) + " d)";
}

Look apply_look(ui::Inspector& insp, LookOptions looks, const io::Run& run) {
  looks.inherit(run.metadata());
  const Look look = looks.resolve(run.model());
  insp.set_look(look.style, look.overlay, look.notes, look.species_colors);
  return look;
}

namespace {
record::VideoSettings settings(int width, int height, int fps) {
  record::VideoSettings v;
  v.width = width;
  v.height = height;
  v.fps = fps;
  return v;
}

class Mp4Sink : public ui::MovieSink {
 public:
  Mp4Sink(const std::string& path, const record::VideoSettings& v) : mp4_(path, v) {}
  void add(const core::Image& img) override { mp4_.add(img); }
  void finish() override { mp4_.finish(); }

 private:
  record::Mp4Writer mp4_;
};
}  // namespace

void RecordFiles::write_png(const std::string& path, const core::Image& img) const {
  record::write_png(path, img, true);
}

void RecordFiles::write_text(const std::string& path, const std::string& text) const {
  io::write_file_atomic(path, text);
}

void RecordFiles::check_movie(int width, int height, int fps) const {
  record::validate(settings(width, height, fps));
}

std::unique_ptr<ui::MovieSink> RecordFiles::open_movie(const std::string& path, int width, int height,
                                                       int fps) const {
  return std::make_unique<Mp4Sink>(path, settings(width, height, fps));
}

void RecordFiles::write_vector(const std::string& path, const std::string& draw_list_csv, double width_m,
                               double height_m, const std::string& caption, const std::string& key) const {
  // The table beside the picture under a temporary name; matplotlib draws it (src/figures/snapshot.py).
  const std::string pid = std::to_string(::getpid());
  const std::filesystem::path table = path + ".table-" + pid + ".csv";
  const std::filesystem::path partial =
      path + ".partial-" + pid + std::filesystem::path(path).extension().string();
  const std::filesystem::path key_file = path + ".key-" + pid + ".tsv";
  io::write_file_atomic(table, draw_list_csv);
  std::vector<std::string> args = {
      table.string(), partial.string(),    core::format_g(width_m, 9), core::format_g(height_m, 9),
      caption,        io::version_string()};
  if (!key.empty() || figure_width_pt > 0) {
    const std::string width =
        figure_width_pt > 0 ? "width_pt\t" + core::format_g(figure_width_pt, 9) + "\n" : "";
    io::write_file_atomic(key_file, key + width);
    args.push_back(key_file.string());
  }
  const int status = run_python(script_path("snapshot.py"), args);
  std::error_code ec;
  std::filesystem::remove(table, ec);
  std::filesystem::remove(key_file, ec);
  if (status != 0) {
    std::filesystem::remove(partial, ec);
    throw core::RuntimeFault(path + ": the matplotlib script snapshot.py failed");
  }
  io::rename_into_place(partial, path);
}

}  // namespace app
