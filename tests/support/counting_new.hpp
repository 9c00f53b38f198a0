#pragma once
// Heap allocations of the calling thread, counted by a replacement of the global operator new
// (every form: plain, array, nothrow, aligned) linked into the test and benchmark binaries
// (tests/support/counting_new.cpp). libroprec's allocations come here too. One thread_local
// increment per allocation; unlike Eigen's EIGEN_RUNTIME_NO_MALLOC assert it works in Release
// (-DNDEBUG) and sees every allocation (std::vector, std::string, std::function, ...).

namespace roprec::test {

/// Allocations made by this thread so far (take differences).
long threadAllocations();

/// Allocations made by f() on this thread.
template <class F>
long allocationsOf(const F& f) {
  const long before = threadAllocations();
  f();
  return threadAllocations() - before;
}

}  // namespace roprec::test
