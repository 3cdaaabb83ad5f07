// A std::vector whose resize leaves new elements of trivial types unwritten
// (default-initialised, not zeroed). For the large arrays a parallel pass
// fills completely right after: zeroing them first is a single-threaded
// pass over fresh pages, and on this project's 2-core VM the first touch of
// memory the process has not used is its dearest part (docs/scaling.md,
// "Where the bytes go"): the filling pass then takes those page faults on
// every thread instead.
#pragma once

#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace zs {

template <class T, class A = std::allocator<T>>
struct DefaultInitAllocator : A {
  using A::A;
  DefaultInitAllocator() = default;
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U, typename std::allocator_traits<A>::template rebind_alloc<U>>;
  };
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    std::allocator_traits<A>::construct(static_cast<A&>(*this), p, std::forward<Args>(args)...);
  }
};

template <class T>
using UninitVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace zs
