// A projection allocates nothing: global operator new counts its calls.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "contact/local_search.hpp"
#include "random_cases.hpp"

namespace {
std::atomic<long> allocations{0};
}

// Every form of the ordinary (not over-aligned) operator new and delete is replaced, so
// that whatever a linked library allocates with one form and frees with another meets
// malloc and free on both sides (the Gmsh library's image codec frees at exit with the
// sized delete what it allocated with the nothrow new).
void* operator new(std::size_t size) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size == 0 ? 1 : size);
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept { return operator new(size, tag); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace exdyn::contact {
namespace {

TEST(LocalSearch, ProjectionAllocatesNothing) {
  {  // the counter sees allocations
    const long before = allocations.load();
    std::vector<double> probe(10);
    EXPECT_GT(allocations.load() - before, 0);
  }
  testing::Random rng(5);
  std::vector<Segment> segments;
  std::vector<Vec3> points;
  for (const SegmentType type : {SegmentType::quad4, SegmentType::quad8}) {
    for (int k = 0; k < 50; ++k) {
      segments.push_back(testing::random_segment(rng, type, testing::Distortion::strong));
      points.push_back(testing::random_point(rng, segments.back(), 1.5, 1.0));
    }
  }
  for (const auto& [method, method_name] : search_method_names) {
    ProjectionSettings st;
    st.method = method;
    const ProjectFn fn = select_method(method);
    const long before = allocations.load();
    double sink = 0.0;
    for (std::size_t k = 0; k < segments.size(); ++k) {
      sink += fn(segments[k], points[k], initial_guess_lsp(segments[k], points[k]), st).distance;
    }
    EXPECT_EQ(allocations.load() - before, 0) << method_name;
    EXPECT_GT(sink, 0.0);
  }
}

}  // namespace
}  // namespace exdyn::contact
