#include "render/cairo_handles.h"

#include <gtest/gtest.h>

#include <type_traits>
#include <utility>

namespace glarecam::render {
namespace {

static_assert(!std::is_copy_constructible_v<CairoContext> &&
              !std::is_copy_assignable_v<CairoContext>);
static_assert(!std::is_copy_constructible_v<CairoSurface> &&
              !std::is_copy_assignable_v<CairoSurface>);
static_assert(std::is_nothrow_move_constructible_v<CairoContext> &&
              std::is_nothrow_move_assignable_v<CairoSurface>);
static_assert(sizeof(CairoContext) == sizeof(cairo_t*), "a handle is just the pointer");

// A stand-in for a Cairo object that counts how often it is destroyed.
struct Counted {
  int* destroyed;
};
void destroyCounted(Counted* object) {
  ++*object->destroyed;
  delete object;
}
using CountedHandle = CairoHandle<Counted, destroyCounted>;

TEST(CairoHandles, DestroyTheObjectOnceWhenTheLastOwnerGoes) {
  int destroyed = 0;
  {
    CountedHandle first(new Counted{&destroyed});
    CountedHandle second = std::move(first);
    EXPECT_EQ(first.get(), nullptr);
    ASSERT_NE(second.get(), nullptr);
    CountedHandle third;
    third = std::move(second);
    EXPECT_EQ(destroyed, 0);
  }
  EXPECT_EQ(destroyed, 1);
}

TEST(CairoHandles, MoveAssignmentDestroysWhatTheTargetHeld) {
  int destroyed_old = 0, destroyed_new = 0;
  CountedHandle target(new Counted{&destroyed_old});
  target = CountedHandle(new Counted{&destroyed_new});
  EXPECT_EQ(destroyed_old, 1);
  EXPECT_EQ(destroyed_new, 0);
  target.reset();
  EXPECT_EQ(destroyed_new, 1);
}

TEST(CairoHandles, ReleaseHandsTheObjectBack) {
  int destroyed = 0;
  Counted* object = nullptr;
  {
    CountedHandle handle(new Counted{&destroyed});
    object = handle.release();
    EXPECT_FALSE(handle);
  }
  EXPECT_EQ(destroyed, 0);
  destroyCounted(object);
  EXPECT_EQ(destroyed, 1);
}

TEST(CairoHandles, ContextWithoutASurfaceIsAnError) {
  const Result<CairoContext> context = createContext(nullptr);
  ASSERT_FALSE(context);
  EXPECT_EQ(context.error().code, ErrorCode::kInternal);
}

}  // namespace
}  // namespace glarecam::render
