// Working storage of a Context's stages (private to the pipeline).
#pragma once
#include <vector>

#include "pipeline/context.hpp"
#include "pipeline/raster_lanes.hpp"
#include "stages/fragment_span.hpp"
#include "stages/fragment_stages.hpp"
#include "stages/convolution.hpp"

namespace passim {

// What Context::assemble_polygon works in and produces: one per thread that assembles.
struct Context::PolygonWork {
  std::vector<ProcessedVertex> polygon, clip_scratch;
  std::vector<RasterVertex> window;  // the polygon drawn, in window coordinates, lit
  GLenum mode = GL_FILL;             // its polygon mode (by facing)
  Vec4 flat_color{};                 // the provoking vertex's colour for the face drawn
  // §2.6.2: whether the vertices' edge flags apply (separate triangles, quads, polygons);
  // otherwise every edge is a boundary edge (strips and fans).
  bool edge_flags = true;
  enum Warning : unsigned { kNonFiniteVertex = 1, kNonFiniteWindow = 2 };
  unsigned warnings = 0;
};

struct Context::Scratch {
  Scratch(Framebuffer& fb, int width)
      : spans(width), stages(fb, counters) {}
  Counters* counters = nullptr;  // the current pass's counters
  SpanBuffers spans;
  FragmentStages stages;  // this thread's: [texture] -> [fog] -> per-fragment operations
  // With more than one thread of rasterization: the lanes primitives are queued to.
  std::unique_ptr<RasterLanes> lanes;
  // Context::rows_on_lanes's splitter.
  RowSplitter rows_on_lanes;
  // Context::primitive_stages_setup's memo: the setup and the options' parts it sets.
  FragmentStagesSetup primitive_setup;
  TriangleOptions primitive_options;
  PolygonWork polygon_work;  // draw_polygon's
  // draw_triangle_batch's: each lane's work (scratch, counters, warnings), and what each
  // chunk of the batch's triangles draws, whichever lane assembled it.
  // Each on cache lines of its own: lanes write them side by side (shared lines cost a fifth
  // of the assembly in cache-line transfers).
  struct alignas(64) BatchLane {
    PolygonWork work;
    Counters counters;  // primitives in, clipped out, clipped, culled
    // The first of its triangles that raised each PolygonWork warning (kNonFiniteVertex,
    // kNonFiniteWindow), SIZE_MAX for none.
    std::size_t first_warned[2] = {SIZE_MAX, SIZE_MAX};
  };
  std::vector<BatchLane> batch_lanes;
  // draw_triangle_batch's distinct vertices: transformed; and, when it can be drawn as it is
  // (simple: finite, trivially inside the clip volume, finite window position), in window
  // coordinates and lit for each face (lit[face], when lighting).
  struct BatchVertex {
    ProcessedVertex vertex;
    RasterVertex window;
    std::array<Vec4, 2> lit{};
    bool simple = false;
  };
  std::vector<BatchVertex> batch_vertices;
  // copy_bands_on_lanes's, one per lane: stages, counters, span buffers and a band of reals
  // (or of codes).
  struct PixelLane : LaneStages {
    using LaneStages::LaneStages;
    std::vector<Rgba> band;
    std::vector<std::uint16_t> band_codes;
  };
  std::vector<std::unique_ptr<PixelLane>> pixel_lanes;
  // Two sets of chunks, used in turn: the raster queue refers to a set's triangles until it
  // is run (chunk_set_queue: the queue that last took a set's triangles).
  struct alignas(64) BatchChunk {
    std::vector<AssembledTriangle> triangles;
    std::vector<TriangleRows> rows;  // each triangle's
  };
  std::vector<BatchChunk> batch_chunks[2];
  std::uint64_t chunk_set_queue[2] = {0, 0};
  int next_chunk_set = 0;
  // A copied rectangle and the convolution's output: kept between calls, so that a copy of
  // the whole window does not map and fault in fresh pages each time.
  std::vector<Rgba> rectangle, rectangle_spare;
};

}  // namespace passim
