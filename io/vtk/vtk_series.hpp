// A run's VTK output: one set of step files per written snapshot, plus a
// series.pvd that indexes them all, in one output directory:
//
//   rods_000000.vtp  frames_000000.vtp  joints_000000.vtp  solids_000000.vtp
//   rods_000001.vtp  ...
//   series.pvd       (open this one in ParaView)
//
// The 6-digit number counts written steps (not calls); the .pvd gives each
// file its snapshot time. Every file, the .pvd included, is replaced
// atomically, and the .pvd is rewritten after every step, so a run killed at
// any moment leaves a directory that ParaView opens, holding every step
// completed so far.
//
// Cadence: write() writes when forced, or when `every` calls have been made
// since the last write. The caller forces the first and final states.
//
// Size: a long run (a million kinetic-damping iterations, a deployment of
// thousands of steps) would write four files per step without end. Once the
// series holds max_steps steps, every other one is removed (files and .pvd
// entries; the first and the latest stay) and `every` doubles: the series
// keeps at most max_steps steps spread over the whole run, however long.
#pragma once

#include <filesystem>
#include <vector>

#include "pvd_collection.hpp"
#include "snapshot.hpp"
#include "solids_file.hpp"
#include "write_options.hpp"

namespace xshell {

struct SeriesOptions {
  int every = 1;  // write every `every`-th call (>= 1)
  VtkFormat format = VtkFormat::Binary;
  bool solids = true;   // also write solids_*.vtp (larger files)
  SolidsOptions solid;  // how solids are swept
  int max_steps = 0;    // thin the series when it holds this many steps (>= 2; 0: never)
  VtkCompression compression = VtkCompression::Lz4;  // of the binary format
};

class VtkSeries {
 public:
  // Creates `directory` (and parents) if needed and writes an empty
  // series.pvd. Throws std::invalid_argument when options.every < 1 and
  // OutputError when the directory or the .pvd cannot be written.
  VtkSeries(std::filesystem::path directory, SeriesOptions options = {});
  VtkSeries(const VtkSeries&) = delete;
  VtkSeries& operator=(const VtkSeries&) = delete;
  // Calls close(); never throws (a failure is reported on stderr).
  ~VtkSeries();

  // Writes the step files of `snapshot` when `force` or when this is the
  // every-th call since the last write, then rewrites series.pvd. Returns
  // whether it wrote. Throws std::invalid_argument for an inconsistent
  // snapshot, OutputError when a file cannot be written (the .pvd then still
  // lists only complete steps), std::logic_error after close().
  bool write(const Snapshot& snapshot, bool force = false);

  // write() in two parts, for a caller that builds the snapshot only when
  // it will be written (and may write it on another thread, one call at a
  // time): due() counts the call and says whether it writes; write_now()
  // writes unconditionally (and throws as write() does).
  bool due(bool force = false);
  void write_now(const Snapshot& snapshot);

  // Rewrites series.pvd a last time; later write() calls throw. Idempotent.
  void close();

  const std::filesystem::path& directory() const { return directory_; }
  std::filesystem::path pvd_path() const { return directory_ / "series.pvd"; }
  int steps_written() const { return steps_written_; }  // ever (the files' numbers)
  int steps_kept() const { return static_cast<int>(kept_.size()); }
  int every() const { return options_.every; }  // doubled by each thinning
  int thinnings() const { return thinnings_; }
  const std::vector<PvdEntry>& entries() const { return entries_; }

 private:
  void write_pvd() const;
  void thin();

  std::filesystem::path directory_;
  SeriesOptions options_;
  std::vector<PvdEntry> entries_;
  int steps_written_ = 0;
  int calls_since_write_ = 0;
  std::vector<int> kept_;  // numbers of the steps in the series, in order
  int thinnings_ = 0;
  bool closed_ = false;
};

// "rods_000042.vtp": the file name of one part of written step `step`.
std::string step_file_name(VtkPart part, int step);

}  // namespace xshell
