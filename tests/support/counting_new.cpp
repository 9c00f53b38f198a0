// The counting global operator new of tests/support/counting_new.hpp, linked into roprec_tests and
// roprec_bench.
#include "tests/support/counting_new.hpp"

#include <algorithm>
#include <cstdint>
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
// Over-aligned blocks on malloc alone (the C runtime of Windows has no std::aligned_alloc): the
// block from malloc is kept in the word just before the aligned address, for countedAlignedFree.
void* countedAligned(std::size_t n, std::align_val_t a) {
  ++t_allocations;
  const std::size_t al = std::max(static_cast<std::size_t>(a), alignof(void*));
  void* const raw = std::malloc(n + al + sizeof(void*));
  if (raw == nullptr) throw std::bad_alloc();
  const std::uintptr_t first = reinterpret_cast<std::uintptr_t>(raw) + sizeof(void*);
  void* const p = reinterpret_cast<void*>((first + al - 1) / al * al);
  static_cast<void**>(p)[-1] = raw;
  return p;
}
void countedAlignedFree(void* p) noexcept {
  if (p != nullptr) std::free(static_cast<void**>(p)[-1]);
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
void operator delete(void* p, std::align_val_t) noexcept { roprec::test::countedAlignedFree(p); }
void operator delete[](void* p, std::align_val_t) noexcept { roprec::test::countedAlignedFree(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  roprec::test::countedAlignedFree(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  roprec::test::countedAlignedFree(p);
}
