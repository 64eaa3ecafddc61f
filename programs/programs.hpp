// The seeds' shadow algorithms as pass programs written against Context
// (docs/programs.md). Each run records its calls as a .pass trace that replays to the
// same bits and counters.
#pragma once
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "trace_io/trace.hpp"
#include "programs/scene.hpp"

namespace passim {

// A setting the program cannot run with (unknown name, a width or filter beyond the
// machine profile's limits): the message names the setting and the limit.
struct ProgramError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct ProgramOptions {
  std::string program = "shadow-map";  // shadow-map, pcf, fast-pcf, mdsm, hw-shadow
  std::string scene = "paper";         // paper, fig8, edges or FILE.obj
  std::string profile = "ideal";
  int color_bits = 8;    // every colour channel
  int depth_bits = 24;
  int accum_bits = 0;    // 0: the default for the colour width (semantics A21)
  int map_size = 0;      // 0: the scene's default
  int width = 800, height = 600;
  int filter = 0;        // 0: the program's default; N of an NxN footprint (pcf 2-4, fast-pcf 2 or 4, mdsm 1-3: k = N²)
  int depths = 1;        // mdsm: n depths per map cell (1-3)
  // Subtracted from the receiver's depth, in steps of the depth encoding (the colour
  // width's ramp; hw-shadow: the depth width). NaN: the paper's one 8-bit step kept as
  // the same depth at every width, 2^(bits−8) steps (hw-shadow: 2^(depth bits−12)).
  double bias = std::numeric_limits<double>::quiet_NaN();
  bool linear = false;   // hw-shadow: LINEAR (2x2 filtered compare) instead of NEAREST
  bool jitter = true;    // pcf: jitter each stratum's sample (else the strata's centres)
  std::uint32_t seed = 1;
  bool intermediates = false;  // also capture every intermediate buffer
  // Internal formats (4, 8, 12 or 16 bits; 0: the smallest sized format holding the colour
  // width): of the ramp and shadow-map textures, and of the counting colour table.
  int texture_bits = 0;
  int table_bits = 0;
  std::string sampling = "jittered";  // reeves: random, gaussian or jittered (Reeves et al. (a), (b), (c))
  // The what-if study's removed stages (whatever the program enables; not recorded in traces).
  bool remove_color_tables = false, remove_convolution = false, remove_color_matrix = false;
  int threads = 1;  // threads of rasterization (Context::set_threads): the same bits at any number
  // Capture the output images (final, attenuation, shadow map...). Off, frames are only
  // rendered, as a displayed frame is: the timing benchmark (bench/programs_bench.cpp). A
  // recorded session captures them regardless (its trace names them).
  bool images = true;
  // Called at the end of every pass (the cross-check, reports/cross_check.hpp).
  Context::PassEndObserver pass_end;
};

struct ProgramInfo {
  std::string name;
  std::string section;  // the paper's section
  std::string summary;
  bool reference = false;  // a double-precision software reference, not a pass program
};
const std::vector<ProgramInfo>& program_list();

// Where the shadow map's samples were taken, for the "same samples" references: the
// offset of each map channel's sample from its texel's lower-left corner, in texels.
struct MapSample {
  int map = 0, channel = 0;
  double dx = 0.5, dy = 0.5;
};

struct ProgramRun {
  ProgramOptions options;
  Scene scene;
  ReplayResult result;                 // settings, context and images (final, attenuation, shadowmap...)
  std::string trace;                   // the recorded .pass text
  std::vector<MapSample> samples;      // the shadow map samples (pcf, fast-pcf, mdsm, shadow-map)
  int map_size = 0;
  int triangles = 0;
  double bias_depth = 0.0;  // the bias in the ramp's [0, 1] depth units (or window depth for hw-shadow)

  const CapturedImage& image(const std::string& name) const;
};

// Runs a program for one frame, recorded; throws ProgramError for settings it cannot
// run with and std::runtime_error for a scene file that cannot be read.
ProgramRun run_program(const ProgramOptions& options);

// A program's context set up once (display list, texgen, ramp), for running whole frames
// again and again (bench/). A recorded session runs one frame.
class ProgramSession {
 public:
  explicit ProgramSession(const ProgramOptions& options, bool record = false);
  ~ProgramSession();
  void frame();
  const ProgramRun& run() const;
  ProgramRun finish();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// A deterministic uniform number in [0, 1): 24 bits of mt19937 (whose output the standard
// fixes, unlike the library's distributions). The programs' jitter and Reeves' samples.
double uniform01(std::mt19937& rng);

// The number of distinct values in a single-channel image, counting values one code
// apart as one level (the paper's 63 and 64).
int count_levels(const CapturedImage& image);

}  // namespace passim
