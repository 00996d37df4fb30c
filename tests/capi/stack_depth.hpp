#pragma once
// How deep a call goes into its thread's stack: the call runs on a pthread whose stack the test
// allocates and paints with a byte pattern; afterwards the lowest overwritten byte shows the depth below
// the thread function's own frame. Used to hold spread_predict to the stack need docs/c-api.md states.
#include <pthread.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace spread::testing {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kSanitizedBuild = true;  // instrumented frames are several times larger
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
inline constexpr bool kSanitizedBuild = true;
#else
inline constexpr bool kSanitizedBuild = false;
#endif
#else
inline constexpr bool kSanitizedBuild = false;
#endif

// The stack need docs/c-api.md states for spread_predict / spread_workspace_predict / spread_trajectory.
inline constexpr std::size_t kStatedStackBytes = 8 * 1024;

namespace detail {
template <typename Call>
struct StackJob {
  Call* call;
  std::uintptr_t entry_address = 0;
  static void* run(void* argument) {
    auto* job = static_cast<StackJob*>(argument);
    volatile char marker = 0;
    job->entry_address = reinterpret_cast<std::uintptr_t>(&marker);
    (*job->call)();
    return nullptr;
  }
};
}  // namespace detail

// Runs call() on a new thread with stack_bytes of stack (at least PTHREAD_STACK_MIN, which also holds the
// thread's descriptor and TLS); returns the bytes below the thread function's frame that it wrote, or 0
// when the thread could not be made.
template <typename Call>
std::size_t stack_depth_of(Call& call, std::size_t stack_bytes) {
  constexpr unsigned char kPaint = 0xA5;
  void* stack = std::aligned_alloc(4096, stack_bytes);
  if (stack == nullptr) return 0;
  std::memset(stack, kPaint, stack_bytes);
  detail::StackJob<Call> job{&call};
  pthread_attr_t attributes;
  pthread_attr_init(&attributes);
  pthread_t thread;
  const bool made = pthread_attr_setstack(&attributes, stack, stack_bytes) == 0 &&
                    pthread_create(&thread, &attributes, &detail::StackJob<Call>::run, &job) == 0;
  if (made) pthread_join(thread, nullptr);
  pthread_attr_destroy(&attributes);
  const auto* bytes = static_cast<const unsigned char*>(stack);
  std::size_t lowest = 0;
  while (lowest < stack_bytes && bytes[lowest] == kPaint) ++lowest;
  const std::uintptr_t deepest = reinterpret_cast<std::uintptr_t>(stack) + lowest;
  const std::size_t depth = made && job.entry_address > deepest ? job.entry_address - deepest : 0;
  std::free(stack);
  return depth;
}

}  // namespace spread::testing
