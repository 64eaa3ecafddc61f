// passim study precision and passim merge (docs/studies.md); a sweep as a Slurm array job,
// passim study status and resume (docs/cluster.md).
#pragma once
#include <string>
#include <vector>

#include "programs/study.hpp"

namespace passim {

struct StudyCommand {
  ProgramOptions base;
  std::string size = "800x600", bits = "4-16", depth_bits, biases, maps, filter, shard = "1/1", out = "study";
  std::vector<std::string> what_if;          // KEY=VALUE changes (study what-if)
  std::string cost_profile = "octane-vpro8";  // the machine the what-if is timed on
  std::string figures = "png,svg,pdf";        // the figures' formats, or "none"
  bool json = false;                          // provenance: JSON instead of the table
  int jobs = 1;
  bool quiet = false;
  // --slurm: the sweep as a Slurm array job, one shard per task, and a merge job after it.
  struct Slurm {
    bool enabled = false;
    bool no_submit = false;  // write the scripts only
    int array_size = 0;   // shards; 0: one per point, at most kDefaultMaxShards
    std::string partition, time, mem, extra;  // as sbatch takes them; empty: the cluster's default
  } slurm;
};
// The default number of shards of a --slurm sweep is its number of points, up to this.
inline constexpr int kDefaultMaxShards = 100;

int study_command(const StudyCommand& command);
// Where a --slurm study stands (its folder): shards done, running, pending, failed, missing.
int study_status_command(const std::string& dir, bool json);
// Submits again the shards of a --slurm study that are missing or failed, and its merge.
int study_resume_command(const std::string& dir);
int provenance_command(const StudyCommand& command);
int what_if_command(const StudyCommand& command);
int merge_command(const std::vector<std::string>& dirs, const std::string& out,
                  const std::string& figures = "png,svg,pdf");

}  // namespace passim
