#include <gtest/gtest.h>

#include "programs/scenes.hpp"
#include "test_util.hpp"

using namespace passim;

TEST(Scenes, BenchSceneHasTheDocumentedTriangleCount) {
  // Ground 16·16·2 = 512; sphere 48 slices × (36·2 − 2) = 3360 (one triangle per quad at the
  // poles); torus 48·32·2 = 3072: 6944, as the peer's scene.
  Context ctx(test::small_config(80, 60));
  setup_bench_scene_view(ctx);
  EXPECT_EQ(emit_bench_scene(ctx), 6944);
  EXPECT_EQ(ctx.total_counters().primitives_in, 6944u);
  EXPECT_EQ(ctx.total_counters().vertices, 3u * 6944u);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}
