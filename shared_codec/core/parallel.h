// SPDX-License-Identifier: Apache-2.0
// Work split over threads so that results never depend on how many there are: parallelFor
// runs the items of a loop on several threads, and each item must compute the same thing on
// any thread (its own output slot, no shared accumulator); the caller combines the slots in
// index order. How many threads a loop may use is the calling thread's budget, set by the
// public Encoder and Decoder for the length of one call (ThreadBudget): the codecs pass no
// thread count around, and a loop inside a parallel loop runs on its one thread.
#pragma once
#include <cstddef>
#include <functional>

namespace animc {

// The threads a request for `threads` means: 0 = every core (at least 1).
unsigned resolveThreads(unsigned threads);

// Sets the calling thread's budget for the lifetime of the object, then restores it.
class ThreadBudget {
 public:
  explicit ThreadBudget(unsigned threads);
  ~ThreadBudget();
  ThreadBudget(const ThreadBudget&) = delete;
  ThreadBudget& operator=(const ThreadBudget&) = delete;
  // The calling thread's budget (1 unless a ThreadBudget says otherwise).
  static unsigned current();

 private:
  unsigned saved_;
};

// Calls item(i) for every i in [0, count), on up to current() threads, the caller's among
// them; returns when all are done. The budget is split between the threads, so a loop inside
// an item runs serially unless there are more threads than items. An exception thrown by an
// item (std::bad_alloc) is rethrown here, in the caller, after the other items have ended.
void parallelFor(size_t count, const std::function<void(size_t i)>& item);

// The same for work that is only worth threads when it is large: count items of about
// item_cost operations each run on one thread below min_cost operations in all.
void parallelFor(size_t count, double item_cost, const std::function<void(size_t i)>& item);

// item(b, begin, end) for the fixed blocks [b x block, min(count, (b + 1) x block)) of
// [0, count), through parallelFor with element_cost the cost of one element: the blocks never
// depend on the thread count, so neither does what each one computes.
void parallelForBlocks(size_t count, size_t block, double element_cost,
                       const std::function<void(size_t b, size_t begin, size_t end)>& item);

// Floats a thread takes at a time in a pass over a frame (a check, a copy): a fixed block, so
// that what each block finds never depends on the thread count.
constexpr size_t kFloatsPerTask = size_t(1) << 18;

// Copies n floats in fixed blocks through parallelForBlocks: a large frame's copy, and the page
// faults of a buffer it fills for the first time, would otherwise hold up one thread.
void copyOnThreads(const float* from, size_t n, float* to);

// Runs side() and main() at once when the budget allows more than one thread: side() on a
// thread of its own with a budget of one, main() on the caller with the caller's budget (the
// two then share the cores with more threads than cores while side() runs). Otherwise one
// after the other. An exception of either is rethrown here after both have ended.
void runBeside(const std::function<void()>& side, const std::function<void()>& main);

}  // namespace animc
