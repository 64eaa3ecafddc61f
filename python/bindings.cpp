// passim's Python module, its compiled half (_passim): runs, traces, studies and costs through
// the same C++ the command line uses. python/passim/__init__.py is the interface researchers
// call; it turns what this returns (JSON text, code arrays) into dicts, numpy arrays and
// DataFrames. Long work releases the GIL (the runs are pure C++).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>

#include "programs/programs.hpp"
#include "programs/reference.hpp"
#include "programs/study.hpp"
#include "reports/cost.hpp"
#include "reports/program_report.hpp"
#include "reports/report.hpp"
#include "trace_io/apitrace_replay.hpp"
#include "trace_io/call_set.hpp"
#include "trace_io/trace.hpp"

namespace py = pybind11;
using namespace passim;

namespace {

// An apitrace replay that stopped (its message names the call), raised as TraceError.
struct ApitraceFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A finished run: a program's or a trace's, with its counters.json document.
struct Run {
  std::shared_ptr<ProgramRun> program;  // a pass program's run
  std::shared_ptr<ReplayResult> replay;  // a trace's replay
  std::shared_ptr<ReferenceRun> reference;  // a double-precision reference (no pipeline)
  std::vector<CapturedImage> reference_image;  // the reference's one image
  std::string report;  // counters.json (or reference.json) as text

  const std::vector<CapturedImage>& images() const {
    if (program) return program->result.images;
    if (replay) return replay->images;
    return reference_image;
  }
  const std::vector<Pass>& passes() const {
    if (program) return program->result.context->passes();
    if (replay) return replay->context->passes();
    throw std::invalid_argument(
        "a double-precision reference runs no pipeline: it has no passes to cost (run a pass program)");
  }
};

// An image's codes as numpy wants them: rows top first (as image files and imshow have them),
// shape (height, width) for one channel, (height, width, channels) otherwise; uint16 up to 16
// bits, uint32 for wider planes (24- and 32-bit depth).
py::array codes_array(const CapturedImage& img) {
  const int widest = *std::max_element(img.bits.begin(), img.bits.end());
  const auto h = static_cast<py::ssize_t>(img.height), w = static_cast<py::ssize_t>(img.width),
             c = static_cast<py::ssize_t>(img.channels);
  std::vector<py::ssize_t> shape{h, w};
  if (img.channels > 1) shape.push_back(c);
  auto fill = [&](auto array) {
    auto* out = array.mutable_data();
    const std::size_t row = static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.channels);
    for (std::size_t y = 0; y < static_cast<std::size_t>(img.height); ++y) {
      const std::size_t src = (static_cast<std::size_t>(img.height) - 1 - y) * row;  // GL: row 0 at the bottom
      for (std::size_t k = 0; k < row; ++k)
        out[y * row + k] = static_cast<typename decltype(array)::value_type>(img.codes[src + k]);
    }
    return py::array(array);
  };
  if (widest <= 16) return fill(py::array_t<std::uint16_t>(shape));
  return fill(py::array_t<std::uint32_t>(shape));
}

template <typename T>
T get(const py::dict& d, const char* key, T fallback) {
  return d.contains(key) && !d[key].is_none() ? d[key].cast<T>() : fallback;
}

// The Python keyword arguments (already checked and named as ProgramOptions' fields by
// passim/__init__.py) as the program's options.
ProgramOptions program_options(const std::string& name, const py::dict& d) {
  ProgramOptions o;
  o.program = name;
  o.scene = get<std::string>(d, "scene", o.scene);
  o.profile = get<std::string>(d, "profile", o.profile);
  o.color_bits = get<int>(d, "color_bits", o.color_bits);
  o.depth_bits = get<int>(d, "depth_bits", o.depth_bits);
  o.accum_bits = get<int>(d, "accum_bits", o.accum_bits);
  o.map_size = get<int>(d, "map_size", o.map_size);
  o.width = get<int>(d, "width", o.width);
  o.height = get<int>(d, "height", o.height);
  o.filter = get<int>(d, "filter", o.filter);
  o.depths = get<int>(d, "depths", o.depths);
  o.bias = get<double>(d, "bias", o.bias);
  o.linear = get<bool>(d, "linear", o.linear);
  o.jitter = get<bool>(d, "jitter", o.jitter);
  o.seed = get<std::uint32_t>(d, "seed", o.seed);
  o.intermediates = get<bool>(d, "intermediates", o.intermediates);
  o.texture_bits = get<int>(d, "texture_bits", o.texture_bits);
  o.table_bits = get<int>(d, "table_bits", o.table_bits);
  o.sampling = get<std::string>(d, "sampling", o.sampling);
  o.threads = get<int>(d, "threads", o.threads);
  if (o.threads < 1 || o.threads > Context::kMaxThreads)
    throw std::invalid_argument(fmt::format("threads={}: 1 to {}", o.threads, Context::kMaxThreads));
  return o;
}

Run run_program_py(const std::string& name, const py::dict& options) {
  const ProgramOptions o = program_options(name, options);
  const auto& list = program_list();
  const auto info = std::find_if(list.begin(), list.end(), [&](const ProgramInfo& p) { return p.name == name; });
  Run r;
  py::gil_scoped_release unlocked;
  if (info != list.end() && info->reference) {
    r.reference = std::make_shared<ReferenceRun>(run_reference(o));
    r.reference_image = {r.reference->image};
    r.report = reference_report(*r.reference, "").dump();
  } else {
    r.program = std::make_shared<ProgramRun>(run_program(o));
    r.report = program_report(*r.program, {}).dump();
  }
  return r;
}

Run run_trace_py(const std::string& path, const py::dict& d) {
  Run r;
  if (looks_like_apitrace(path)) {
    ApitraceOptions o;
    o.profile = get<std::string>(d, "profile", o.profile);
    o.color_bits = get<int>(d, "color_bits", o.color_bits);
    o.depth_bits = get<int>(d, "depth_bits", o.depth_bits);
    o.stencil_bits = get<int>(d, "stencil_bits", o.stencil_bits);
    o.accum_bits = get<int>(d, "accum_bits", o.accum_bits);
    o.width = get<int>(d, "width", o.width);
    o.height = get<int>(d, "height", o.height);
    o.strict = get<bool>(d, "strict", o.strict);
    o.max_memory = get<std::uint64_t>(d, "max_memory", o.max_memory);
    const std::string snapshot = get<std::string>(d, "snapshot", "");
    if (!snapshot.empty()) o.snapshot = CallSet::parse(snapshot);
    o.snapshot_at_flush = get<bool>(d, "snapshot_at_flush", false);
    ApitraceReplay a;
    {
      py::gil_scoped_release unlocked;
      a = replay_apitrace(path, o);
    }
    if (a.error) throw ApitraceFailure(*a.error);
    r.replay = std::make_shared<ReplayResult>(std::move(a.result));
  } else {
    ReplayOptions o;
    o.strict = get<bool>(d, "strict", o.strict);
    o.max_memory = get<std::uint64_t>(d, "max_memory", o.max_memory);
    if (d.contains("allow_files"))
      for (const py::handle& f : d["allow_files"]) o.allow_files.emplace_back(py::str(f).cast<std::string>());
    py::gil_scoped_release unlocked;
    r.replay = std::make_shared<ReplayResult>(replay_trace(path, o));
  }
  r.report = run_report(*r.replay, path, {}).dump();
  return r;
}

// A precision study (docs/studies.md): the rows as study.json holds them, as JSON text.
std::string study_py(const std::string& name, const py::dict& base, const std::vector<int>& color_bits,
                     const std::vector<int>& depth_bits, const std::vector<double>& biases,
                     const std::vector<int>& maps, int jobs) {
  StudySweep sweep;
  sweep.base = program_options(name, base);
  sweep.color_bits = color_bits;
  sweep.depth_bits = depth_bits;
  sweep.biases = biases;
  sweep.map_sizes = maps;
  if (jobs < 1 || jobs > 256) throw std::invalid_argument(fmt::format("jobs={}: 1 to 256", jobs));
  py::gil_scoped_release unlocked;
  const std::vector<StudyRow> rows = run_study(sweep, jobs, 0, 1);
  return study_json(sweep_description(sweep), rows, 0, 1).dump();
}

std::string cost_py(const Run& run, const std::string& profile) {
  return cost_json(frame_cost(run.passes(), timed_profile(profile))).dump();
}

}  // namespace

PYBIND11_MODULE(_passim, m) {
  m.doc() = "passim's compiled core; use the passim package (python/passim/__init__.py)";
  // The command line's errors, as exceptions with its messages: a run's bad setting, a
  // trace's error (naming file:line or the call); invalid arguments become ValueError.
  static py::exception<ProgramError> program_error(m, "ProgramError", PyExc_RuntimeError);
  static py::exception<TraceError> trace_error(m, "TraceError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ProgramError& e) {
      program_error(e.what());
    } catch (const TraceError& e) {
      trace_error(e.what());
    } catch (const ApitraceFailure& e) {
      trace_error(e.what());
    }
  });
  py::class_<Run>(m, "Run")
      .def("report", [](const Run& r) { return r.report; })
      .def("images", [](const Run& r) {
        py::list out;
        for (const CapturedImage& img : r.images()) {
          py::list bits;
          for (int c = 0; c < std::min(img.channels, 4); ++c) bits.append(img.bits[static_cast<std::size_t>(c)]);
          out.append(py::make_tuple(img.name, img.plane, bits, codes_array(img)));
        }
        return out;
      })
      .def("levels", [](const Run& r) {
        for (const CapturedImage& img : r.images())
          if (img.name == "attenuation") return py::object(py::int_(count_levels(img)));
        return py::object(py::none());
      });
  m.def("run_program", &run_program_py, py::arg("name"), py::arg("options"));
  m.def("run_trace", &run_trace_py, py::arg("path"), py::arg("options"));
  m.def("study", &study_py, py::arg("name"), py::arg("base"), py::arg("color_bits"), py::arg("depth_bits"),
        py::arg("biases"), py::arg("maps"), py::arg("jobs"));
  m.def("cost", &cost_py, py::arg("run"), py::arg("profile"));
  m.def("programs", [] {
    py::list out;
    for (const ProgramInfo& p : program_list()) out.append(py::make_tuple(p.name, p.section, p.summary, p.reference));
    return out;
  });
  m.def("profiles", [] {
    py::list out;
    for (const MachineProfile& p : machine_profiles())
      out.append(py::make_tuple(p.name, p.color_bits[0], p.rates.triangles > 0.0));
    return out;
  });
}
