// Heap allocations of the calling thread, counted by a replacement of the global operator new in
// the benchmark binary (every form; libroprec's allocations come here too), for the benchmarks
// that report allocations per hole (precision_bench.cpp: BM_Compensate1000). One thread_local
// increment per allocation: no effect on the timings worth measuring.
#include <cstdlib>
#include <new>

namespace roprec::bench {
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

/// Allocations made by this thread so far.
long threadAllocations() { return t_allocations; }
}  // namespace roprec::bench

void* operator new(std::size_t n) { return roprec::bench::counted(n); }
void* operator new[](std::size_t n) { return roprec::bench::counted(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return roprec::bench::counted(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return roprec::bench::counted(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new(std::size_t n, std::align_val_t a) {
  return roprec::bench::countedAligned(n, a);
}
void* operator new[](std::size_t n, std::align_val_t a) {
  return roprec::bench::countedAligned(n, a);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
