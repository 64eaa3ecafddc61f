// Precision studies (docs/studies.md): a program run over a sweep of settings, each run
// measured against the double-precision reference of the same algorithm on the same scene.
#pragma once
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "programs/programs.hpp"
#include "programs/reference.hpp"

namespace passim {

struct StudySweep {
  ProgramOptions base;               // program, scene, filter, depths, size ...
  std::vector<int> color_bits;       // default 4..16
  std::vector<int> depth_bits;       // default {base.depth_bits}
  std::vector<double> biases;        // in 8-bit steps of depth; NaN: the program's default
  std::vector<int> map_sizes;        // 0: the scene's
  // The sweep's points in a fixed order: bits vary fastest, then depth, bias, map.
  std::vector<ProgramOptions> points() const;
  // Identifies the sweep (every setting), so slices of different sweeps are not merged.
  std::string id() const;
};

struct StudyRow {
  int index = 0;  // the point's place in the sweep
  int color_bits = 0, depth_bits = 0, map_size = 0;
  double bias_steps8 = 0.0;  // the bias in 8-bit steps of depth
  int levels = 0;
  double mean_abs_error = 0.0, precision_bits = 0.0;
  int wrong_pixels = 0;  // pixels more than one code away from the reference (AttenuationError)
  // Misclassified pixels against the double-precision reference (what the widths cost) and
  // against the exact shadow test (the algorithm as a whole, sampling included).
  Misclassified reference, exact;
  int surfaces = 0;
  double depth_step_world = 0.0;  // one code of the depth encoding, in world units along the light's axis
  CapturedImage edge;  // a shadow edge of the final image, magnified 4x, 8-bit RGB (not in the tables)
};

// A run's attenuation against its algorithm in double precision (exact_attenuation).
struct AttenuationError {
  double mean_abs = 0.0, precision_bits = 0.0;
  // Pixels whose attenuation is more than one code of its width away from the reference: a
  // different count of shadowed samples, not the rounding of the right one. (The largest
  // error, which this replaced, is a whole step at some pixel at every width.)
  int wrong_pixels = 0;
};
AttenuationError attenuation_error(const ProgramRun& run);
AttenuationError attenuation_error(const ProgramRun& run, const std::vector<double>& exact);

// Precision provenance: the run as given, then with one stage at a time widened to its
// widest (texture formats 16 bits, the colour table 16, accumulation 32, the colour planes
// 16); what each gains says where information is lost.
struct ProvenanceRow {
  std::string stage;     // "as given" or the stage widened
  std::string widening;  // "the colour planes to 16 bits" ("" for the run as given)
  int levels = 0;
  AttenuationError error;
};
// `progress` is called before each of the runs (and their references), with the number done.
std::vector<ProvenanceRow> precision_provenance(
    const ProgramOptions& options, const std::function<void(int done, int total, const std::string& next)>& progress = {});
// The runs' document (provenance --json): the settings, each row with the bits its widening
// recovers, and the statement "widening X recovers N bits" for the first stage in pipeline
// order whose widening alone recovers more than `threshold` bits (null when none does).
nlohmann::json provenance_json(const ProgramOptions& options, const std::vector<ProvenanceRow>& rows,
                               double threshold = 0.05);

// Runs one point of the sweep (deterministic, independent of every other point).
StudyRow run_study_point(const ProgramOptions& point, int index);

// Runs the points with index % shard_count == shard_index (all when shard_count = 1) on
// `jobs` threads; rows come back in sweep order whatever the thread count. `progress`
// is called after each finished point (from one thread at a time).
std::vector<StudyRow> run_study(const StudySweep& sweep, int jobs, int shard_index, int shard_count,
                                const std::function<void(int done, int total)>& progress = {});

// The study's headline (docs/studies.md, "The headline"): the 8-vs-12-bit claim as this sweep
// measures it — whether 12 bits has fewer misclassified pixels (against the double-precision
// reference) and fewer light leaks (shadowed pixels left lit, against the exact shadow test)
// than 8 at every bias, with the counts, and self-shadowing at both widths beside them. Null
// when the sweep does not hold both 8 and 12 bits.
nlohmann::json study_headline(const std::vector<StudyRow>& rows);

// The files' contents: CSV (one row per point, a header) and JSON (sweep + rows).
std::string study_csv(const std::vector<StudyRow>& rows);
// The sweep's description (its settings, id and number of points), as study.json holds it.
nlohmann::json sweep_description(const StudySweep& sweep);
nlohmann::json study_json(const nlohmann::json& sweep_description, const std::vector<StudyRow>& rows, int shard_index,
                          int shard_count);
// Joins slices (their study.json documents): the same sweep, every point once. Throws
// std::runtime_error naming the problem.
std::vector<StudyRow> merge_study(const std::vector<nlohmann::json>& slices, nlohmann::json& sweep_out);

}  // namespace passim
