// Context: the display lists' fast path — a block of triangles drawn as a whole, each
// distinct vertex processed once, on every raster lane — standing in for its calls run one by
// one (context_lists.cpp, the reference; stages/kernel_paths.hpp chooses, the cross-check
// compares).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "pipeline/checked_size.hpp"
#include "pipeline/context.hpp"
#include "pipeline/context_internal.hpp"
#include "pipeline/context_scratch.hpp"
#include "pipeline/fixed_point.hpp"
#include "stages/clipping.hpp"
#include "stages/lighting.hpp"
#include "stages/rasterizer.hpp"

namespace passim {

// ---------------------------------------------------------------- display-list blocks drawn as a whole
void Context::draw_triangle_batch(const TriangleBatch& batch, const std::vector<Call>& calls) {
  // Its glBegin has run. The batch is drawn as its calls would draw it, one by one, unless
  // it began separate triangles with every polygon filled (points and lines are drawn by
  // draw_polygon alone).
  if (!in_begin_ || begin_mode_ != GL_TRIANGLES || !prim_vertices_.empty() || polygon_.mode_front != GL_FILL ||
      polygon_.mode_back != GL_FILL) {
    for (std::size_t k = batch.begin_call + 1; k < batch.end_call; ++k) calls[k].info->invoke(*this, calls[k].args);
    return;
  }
  Counters& pass = counters();
  // The tasks below run on every lane that takes part, or on this thread alone.
  RasterLanes* lanes = scratch_->lanes.get();
  const auto run_task = [&](const std::function<void(int)>& task) { lanes ? lanes->run_task(task) : task(0); };
  prepare_vertex_processing();
  const Vec3 start_normal = current_.normal;
  const std::size_t count = batch.vertices.size(), triangles = count / 3;
  pass.vertices += 3 * triangles;
  count_vertex_processing(pass, 3 * triangles);
  // The distinct vertices, in chunks shared out among the lanes (ChunkClaims: each lane
  // starts on its own share, as it does with the triangles below, which then read mostly
  // vertices their own lane made): transformed, and those that can be drawn as they are (see
  // Scratch::BatchVertex) placed in the window and lit.
  const std::size_t distinct = batch.positions.size();
  std::vector<Scratch::BatchVertex>& vertices = scratch_->batch_vertices;
  if (vertices.size() < distinct) vertices.resize(distinct);
  const ClipPlanes planes = clip_planes_of(transform_);
  const int faces = lighting_.enabled && lighting_.two_side ? 2 : 1;
  const int lane_count = lanes ? lanes->lanes() : 1;
  constexpr std::size_t kChunkVertices = 64;
  ChunkClaims vertex_chunks((distinct + kChunkVertices - 1) / kChunkVertices, lane_count);
  run_task([&](int lane) {
    for (std::size_t chunk = vertex_chunks.next(lane); chunk < vertex_chunks.count(); chunk = vertex_chunks.next(lane)) {
      const std::size_t first = chunk * kChunkVertices;
      for (std::size_t i = first; i < std::min(distinct, first + kChunkVertices); ++i) {
        Scratch::BatchVertex& d = vertices[i];
        d.vertex = transform_vertex(batch.positions[i], batch.inherits[i] ? start_normal : batch.normals[i]);
        d.window = to_window(d.vertex, 0);
        d.simple = finite_vertex(d.vertex) && trivially_inside(d.vertex, planes) && d.window.finite_position();
        if (!d.simple || !d.vertex.light_pending) continue;
        for (int face = 0; face < faces; ++face) {
          ProcessedVertex lit = d.vertex;
          light_pending_vertex(lit, face);
          d.lit[static_cast<std::size_t>(face)] = lit.color[static_cast<std::size_t>(face)];
        }
      }
    }
  });
  // Chunks of triangles go to the lanes the same way (a worker still rasterizing what is
  // queued joins when it is free, or not at all; the task touches nothing rasterization
  // does: it reads state and writes its lane's counters and its chunks); each chunk is
  // assembled the same way by any lane, and the chunks are queued in order.
  constexpr std::size_t kChunkTriangles = 32;
  const std::size_t chunks = (triangles + kChunkTriangles - 1) / kChunkTriangles;
  std::vector<Scratch::BatchLane>& works = scratch_->batch_lanes;
  // The chunks' storage: the set the raster queue may still refer to is run first.
  const int set = scratch_->next_chunk_set;
  scratch_->next_chunk_set = 1 - set;
  if (lanes && lanes->pending() && scratch_->chunk_set_queue[set] == lanes->queue_serial()) lanes->flush(pass);
  std::vector<Scratch::BatchChunk>& drawn = scratch_->batch_chunks[set];
  works.resize(lanes ? static_cast<std::size_t>(lanes->lanes()) : 1);
  if (drawn.size() < chunks) drawn.resize(chunks);
  for (Scratch::BatchLane& share : works) {  // a lane that takes no part adds nothing
    share.counters = Counters{};
    share.first_warned[0] = share.first_warned[1] = SIZE_MAX;
  }
  ChunkClaims triangle_chunks(chunks, lane_count);
  run_task([&](int lane) {
    Scratch::BatchLane& share = works[static_cast<std::size_t>(lane)];
    PolygonWork& work = share.work;
    Counters& counted = share.counters;
    for (std::size_t chunk = triangle_chunks.next(lane); chunk < chunks; chunk = triangle_chunks.next(lane)) {
      std::vector<AssembledTriangle>& out = drawn[chunk].triangles;
      std::vector<TriangleRows>& out_rows = drawn[chunk].rows;
      out.clear();
      out_rows.clear();
      const std::size_t last = std::min(triangles, (chunk + 1) * kChunkTriangles);
      for (std::size_t t = chunk * kChunkTriangles; t < last; ++t) {
        const Scratch::BatchVertex* d[3] = {&vertices[batch.vertices[3 * t]], &vertices[batch.vertices[3 * t + 1]],
                                            &vertices[batch.vertices[3 * t + 2]]};
        if (d[0]->simple && d[1]->simple && d[2]->simple) {
          // What assemble_polygon does with a triangle that is not clipped, from the vertices'
          // window positions and colours found once.
          ++counted.primitives_in;
          const Facing facing = triangle_facing(d[0]->window, d[1]->window, d[2]->window, counted);
          if (!facing.drawn) continue;
          const auto face = static_cast<std::size_t>(facing.face);
          const bool lit = d[2]->vertex.light_pending;  // the provoking vertex
          // Made where it is kept (a triangle is 352 bytes: copying one made aside was a third
          // of the task's time).
          AssembledTriangle& drawn_triangle =
              out.emplace_back(d[0]->window, d[1]->window, d[2]->window,
                               lit ? d[2]->lit[face] : d[2]->vertex.color[face], t);
          for (int k = 0; k < 3; ++k)
            if (lit || face == 1) drawn_triangle.v[k].color = lit ? d[k]->lit[face] : d[k]->vertex.color[face];
          out_rows.push_back(triangle_rows(drawn_triangle.v[0], drawn_triangle.v[1], drawn_triangle.v[2],
                                           profile_.limits.subpixel_bits, fb_.config.height));
          continue;
        }
        const ProcessedVertex* p[3] = {&d[0]->vertex, &d[1]->vertex, &d[2]->vertex};
        work.warnings = 0;
        const bool drawn_here = assemble_polygon(p, 3, d[2]->vertex, work, counted);
        for (unsigned kind = 0; kind < 2; ++kind)
          if (work.warnings & (1u << kind)) share.first_warned[kind] = std::min(share.first_warned[kind], t);
        if (!drawn_here) continue;
        const std::vector<RasterVertex>& win = work.window;
        for (std::size_t k = 1; k + 1 < win.size(); ++k) {
          out.emplace_back(win[0], win[k], win[k + 1], work.flat_color, t);
          out_rows.push_back(triangle_rows(win[0], win[k], win[k + 1], profile_.limits.subpixel_bits, fb_.config.height));
        }
      }
    }
  });
  // The lanes' counters (sums); the warnings and the stage setup (which may warn too, and is
  // made at the first triangle drawn) in the order the calls one by one would meet them;
  // then the triangles to the raster queue in order.
  std::size_t first_warned[2] = {SIZE_MAX, SIZE_MAX}, first_drawn = SIZE_MAX;
  for (const Scratch::BatchLane& share : works) {
    pass += share.counters;
    for (int kind = 0; kind < 2; ++kind) first_warned[kind] = std::min(first_warned[kind], share.first_warned[kind]);
  }
  for (std::size_t chunk = 0; chunk < chunks && first_drawn == SIZE_MAX; ++chunk)
    if (!drawn[chunk].triangles.empty()) first_drawn = drawn[chunk].triangles.front().source;
  std::array<std::pair<std::size_t, int>, 3> events{
      {{first_warned[0], 0}, {first_warned[1], 1}, {first_drawn, 2}}};
  std::sort(events.begin(), events.end());
  TriangleOptions setup_options;
  const FragmentStagesSetup* setup = nullptr;
  for (const auto& [at, what] : events) {
    if (at == SIZE_MAX) break;
    if (what == 2) setup = &primitive_stages_setup(setup_options);
    else note_polygon_warnings(what == 0 ? PolygonWork::kNonFiniteVertex : PolygonWork::kNonFiniteWindow);
  }
  if (setup && lanes) {
    raster_queued_ = true;
    // By reference (each triangle's options are these but for its flat colour).
    const TriangleOptions options = polygon_options(setup_options, Vec4{});
    for (std::size_t chunk = 0; chunk < chunks; ++chunk)
      lanes->triangles(drawn[chunk].triangles.data(), drawn[chunk].rows.data(), drawn[chunk].triangles.size(), options,
                       *setup, pass);
    scratch_->chunk_set_queue[set] = lanes->queue_serial();
  } else if (setup) {
    TriangleOptions options = polygon_options(setup_options, Vec4{});
    for (std::size_t chunk = 0; chunk < chunks; ++chunk)
      for (std::size_t t = 0; t < drawn[chunk].triangles.size(); ++t) {
        const AssembledTriangle& triangle = drawn[chunk].triangles[t];
        options.flat_color = triangle.flat_color;
        rasterize_triangle(triangle.v[0], triangle.v[1], triangle.v[2], options, setup->target, scratch_->spans,
                           fragment_sink(), pass, &drawn[chunk].rows[t]);
      }
  }
  prim_vertex_count_ += 3 * triangles;
  // The vertices after the last whole triangle wait for the next, as their calls would leave them.
  for (std::size_t i = 3 * triangles; i < count; ++i) {
    const std::uint32_t v = batch.vertices[i];
    current_.normal = batch.inherits[v] ? start_normal : batch.normals[v];
    submit_vertex(batch.positions[v]);
  }
  if (batch.sets_normal) current_.normal = batch.last_normal;
}

}  // namespace passim
