#include <gtest/gtest.h>
#include "pipeline/context.hpp"
TEST(Smoke, Builds) { passim::Context c(passim::FramebufferConfig{}); EXPECT_EQ(c.glGetError(), GLenum(GL_NO_ERROR)); }
