// The counting global operator new of tests/support/counting_new.hpp, linked into roprec_tests and
// roprec_bench.
#include "tests/support/counting_new.hpp"

#include <cstdlib>
#include <new>

namespace roprec::test {
namespace {
thread_local long t_allocations = 0;

void* counted(std::size_t n) {
  ++t_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* countedAligned(std::size_t n, std::align_val_t a) {
  ++t_allocations;
  const std::size_t al = static_cast<std::size_t>(a);
  if (void* p = std::aligned_alloc(al, (n + al - 1) / al * al)) return p;
  throw std::bad_alloc();
}
}  // namespace

long threadAllocations() { return t_allocations; }
}  // namespace roprec::test

void* operator new(std::size_t n) { return roprec::test::counted(n); }
void* operator new[](std::size_t n) { return roprec::test::counted(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return roprec::test::counted(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return roprec::test::counted(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new(std::size_t n, std::align_val_t a) { return roprec::test::countedAligned(n, a); }
void* operator new[](std::size_t n, std::align_val_t a) {
  return roprec::test::countedAligned(n, a);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
