#pragma once
// Counts every heap allocation of the test program that includes this header (in exactly one of
// its translation units): replacement operators new/delete on malloc/free. GCC's
// mismatched-new-delete warning does not know that they are replacements.
#include <atomic>
#include <cstdlib>
#include <new>

namespace flexgait::testing {
inline std::atomic<long> g_allocations{0};
}  // namespace flexgait::testing

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  ++flexgait::testing::g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
#pragma GCC diagnostic pop
