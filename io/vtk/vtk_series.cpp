#include "vtk_series.hpp"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <system_error>

#include "frames_file.hpp"
#include "io/atomic_file.hpp"
#include "io/output_error.hpp"
#include "joints_file.hpp"
#include "rods_file.hpp"

namespace xshell {

std::string step_file_name(VtkPart part, int step) {
  char number[32];
  std::snprintf(number, sizeof number, "%06d", step);
  return std::string(part_name(part)) + "_" + number + ".vtp";
}

VtkSeries::VtkSeries(std::filesystem::path directory, SeriesOptions options)
    : directory_(std::move(directory)), options_(options) {
  if (options_.every < 1)
    throw std::invalid_argument("VTK series: `every` must be at least 1, got " +
                                std::to_string(options_.every));
  std::error_code error;
  std::filesystem::create_directories(directory_, error);
  if (error) throw OutputError(directory_, error.message());
  write_pvd();
}

VtkSeries::~VtkSeries() {
  try {
    close();
  } catch (const std::exception& e) {
    std::cerr << "xshell: closing the VTK series failed: " << e.what() << '\n';
  }
}

bool VtkSeries::write(const Snapshot& snapshot, bool force) {
  if (!due(force)) return false;
  write_now(snapshot);
  return true;
}

bool VtkSeries::due(bool force) {
  if (closed_) throw std::logic_error("VTK series: write() after close()");
  ++calls_since_write_;
  return force || calls_since_write_ >= options_.every;
}

void VtkSeries::write_now(const Snapshot& snapshot) {
  if (closed_) throw std::logic_error("VTK series: write() after close()");
  validate(snapshot);

  const WriteOptions format{options_.format, options_.compression};
  std::vector<PvdEntry> step;  // the parts written so far
  auto write_part = [&](VtkPart part, auto&& write_file) {
    const std::string file = step_file_name(part, steps_written_);
    write_file(directory_ / file);
    step.push_back({snapshot.time, part, file});
  };
  try {
    write_part(VtkPart::Rods, [&](const auto& path) { write_rods_file(snapshot, path, format); });
    write_part(VtkPart::Frames,
               [&](const auto& path) { write_frames_file(snapshot, path, format); });
    write_part(VtkPart::Joints,
               [&](const auto& path) { write_joints_file(snapshot, path, format); });
    if (options_.solids)
      write_part(VtkPart::Solids, [&](const auto& path) {
        write_solids_file(snapshot, path, format, options_.solid);
      });
  } catch (...) {
    // No orphans: the files of an incomplete step leave with it.
    for (const PvdEntry& entry : step) {
      std::error_code ignored;
      std::filesystem::remove(directory_ / entry.file, ignored);
    }
    throw;
  }

  // Only a complete step enters the index.
  entries_.insert(entries_.end(), step.begin(), step.end());
  kept_.push_back(steps_written_);
  ++steps_written_;
  calls_since_write_ = 0;
  if (options_.max_steps >= 2 && steps_kept() >= options_.max_steps) thin();
  write_pvd();
}

// Keeps the steps at even positions and the latest; removes the others'
// files after their .pvd entries (a run killed between the two leaves the
// files unindexed, never an entry without its file).
void VtkSeries::thin() {
  std::vector<int> kept;
  std::vector<std::string> removed;
  for (std::size_t i = 0; i < kept_.size(); ++i) {
    if (i % 2 == 0 || i + 1 == kept_.size()) {
      kept.push_back(kept_[i]);
      continue;
    }
    for (VtkPart part : {VtkPart::Rods, VtkPart::Frames, VtkPart::Joints, VtkPart::Solids})
      removed.push_back(step_file_name(part, kept_[i]));
  }
  std::vector<PvdEntry> entries;
  for (const PvdEntry& entry : entries_)
    if (std::find(removed.begin(), removed.end(), entry.file) == removed.end())
      entries.push_back(entry);
  entries_ = std::move(entries);
  kept_ = std::move(kept);
  write_pvd();
  for (const std::string& file : removed) {
    std::error_code ignored;
    std::filesystem::remove(directory_ / file, ignored);
  }
  options_.every *= 2;
  ++thinnings_;
}

void VtkSeries::close() {
  if (closed_) return;
  closed_ = true;
  write_pvd();
}

void VtkSeries::write_pvd() const { write_file_atomically(pvd_path(), pvd_text(entries_)); }

}  // namespace xshell
