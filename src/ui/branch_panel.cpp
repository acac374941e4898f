// The inspector's "what if" tab (ui/panels.h): branch here, remove the selected grain, kick now, continue,
// save as a run, branch off; each button runs the script line that repeats it (ui/inspector_branch.cpp).
#include <imgui.h>

#include <string>

#include "core/format.h"
#include "ui/panels.h"

namespace ui {

void draw_branch(Inspector& insp, PanelState& ps) {
  // "What if": the script's branch lines as buttons (ui/inspector_branch.cpp).
  if (!insp.can_branch()) {
    ImGui::TextWrapped("this run cannot be re-simulated (imported from lab data, or a trajectory alone)");
    return;
  }
  const Branch* b = insp.branch();
  if (!b) {
    ImGui::TextWrapped("re-simulate the run from this frame, change it, and watch both side by side");
    if (ImGui::Button("branch here"))
      act(insp, ps, [&] { insp.execute("branch at " + std::to_string(insp.frame_index())); });
    remember(ps, "branch here");
    return;
  }
  ImGui::Text("branch from frame %ld, now t = %.3f s", b->from_frame(), b->time());
  ImGui::BeginDisabled(insp.selected < 0 || b->saved());
  const std::string remove = insp.selected < 0 ? std::string("remove the selected grain")
                                               : "remove grain " + std::to_string(insp.selected);
  if (ImGui::Button(remove.c_str()))
    act(insp, ps, [&] { insp.execute("remove grain " + std::to_string(insp.selected)); });
  remember(ps, "remove grain");
  ImGui::EndDisabled();
  ImGui::BeginDisabled(b->saved());
  ImGui::SetNextItemWidth(8 * ImGui::GetFontSize());
  ImGui::SliderFloat("##kick", &ps.kick_dv, 0.01f, 2.0f, "%.2f m/s", ImGuiSliderFlags_Logarithmic);
  ImGui::SameLine();
  if (ImGui::Button("kick now"))
    act(insp, ps, [&] { insp.execute("kick " + core::format_g(ps.kick_dv, 3)); });
  remember(ps, "kick now");
  if (ImGui::Button("continue 1 frame"))
    act(insp, ps,
        [&] { insp.execute("continue " + core::format_g(insp.trajectory().frame_interval(), 17)); });
  ImGui::SameLine();
  if (ImGui::Button("continue 1 s")) act(insp, ps, [&] { insp.execute("continue 1"); });
  remember(ps, "continue 1 s");
  ImGui::SetNextItemWidth(12 * ImGui::GetFontSize());
  ImGui::InputText("##branch_path", ps.branch_path, sizeof ps.branch_path);
  ImGui::SameLine();
  if (ImGui::Button("save as a run"))
    act(
        insp, ps, [&] { insp.execute(std::string("save branch ") + ps.branch_path); }, true);
  remember(ps, "save branch");
  ImGui::EndDisabled();
  if (ImGui::Button("branch off")) act(insp, ps, [&] { insp.execute("branch off"); });
  remember(ps, "branch off");
  b = insp.branch();  // the button may have ended it
  if (!b) return;
  // What was changed, below the buttons (they stay where they are as the list grows).
  if (b->saved()) ImGui::TextDisabled("saved as a run (it ended there)");
  for (const auto& c : b->changes()) ImGui::BulletText("%s", c.c_str());
}

}  // namespace ui
