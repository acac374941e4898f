// sim::Silo's changes by hand between steps ("what if": the inspector's branches, app/services/branch.h): a
// grain taken out as the clog rule takes an arch's, a species' dipole moment changed.
#include <string>
#include <vector>

#include "core/error.h"
#include "sim/silo.h"

namespace sim {

const core::StepEvents& Silo::remove_by_hand(const std::vector<int>& ids) {
  last_.clear();
  for (int id : ids)
    if (id < 0 || id >= static_cast<int>(radius_.size()) ||
        (!parked_.empty() && parked_[static_cast<size_t>(id)]))
      throw core::InputError("remove: grain " + std::to_string(id) +
                             " is not in the container (ids run from 0 to " +
                             std::to_string(radius_.size() - 1) + ")");
  if (!clogs_.state().open) {
    // Flowing: no clog to end, no arch to record; the grains go back on top of the column.
    for (int id : ids) reinject(id);
    return last_;
  }
  // An open clog ends at the removal as it would by the rule, with the removed grains as the row of
  // arches.csv (what a "what if" branch changed: app/services/branch.h).
  core::ArchEvent ev;
  ev.t = t_;
  ev.clog_duration = clogs_.since_last(t_);
  ev.method = arch_method_;
  ev.ids = ids;
  remove_arch(std::move(ev), positions());
  record_closed_clogs();
  pending_.append(last_);
  return last_;
}

void Silo::set_dipole(int species, double moment) {
  // Rebuilt in id order, as the fill made it; grains that left (a drain) keep none.
  std::vector<double> per(radius_.size(), 0.0);
  for (size_t k = 0; k < dipole_ids_.size(); ++k)
    per[static_cast<size_t>(dipole_ids_[k])] = dipole_moment_[k];
  for (size_t id = 0; id < per.size(); ++id)
    if (static_cast<int>(species_[id]) == species && (parked_.empty() || !parked_[id])) per[id] = moment;
  dipole_ids_.clear();
  dipole_moment_.clear();
  for (size_t id = 0; id < per.size(); ++id)
    if (per[id] > 0) dipole_ids_.push_back(static_cast<int>(id)), dipole_moment_.push_back(per[id]);
}

}  // namespace sim
