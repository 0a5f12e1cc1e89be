// SPDX-License-Identifier: Apache-2.0
#include "core/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace animc {
namespace {

thread_local unsigned budget = 1;

// Below this many operations a loop is not worth the start of a thread (tens of microseconds).
constexpr double kMinParallelCost = 2e5;

}  // namespace

unsigned resolveThreads(unsigned threads) {
  if (threads > 0) return threads;
  return std::max(1u, std::thread::hardware_concurrency());
}

ThreadBudget::ThreadBudget(unsigned threads) : saved_(budget) { budget = resolveThreads(threads); }
ThreadBudget::~ThreadBudget() { budget = saved_; }
unsigned ThreadBudget::current() { return budget; }

void parallelFor(size_t count, const std::function<void(size_t)>& item) {
  const unsigned threads = unsigned(std::min<size_t>(budget, count));
  if (threads <= 1) {
    for (size_t i = 0; i < count; ++i) item(i);
    return;
  }
  const unsigned share = std::max(1u, budget / threads);
  std::atomic<size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto work = [&] {
    ThreadBudget inner(share);
    for (size_t i; (i = next.fetch_add(1)) < count;) {
      try {
        item(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next = count;  // the items not started are skipped
      }
    }
  };
  std::vector<std::thread> helpers;
  try {
    for (unsigned t = 1; t < threads; ++t) helpers.emplace_back(work);
  } catch (const std::system_error&) {
    // No more threads to be had: the ones started and the caller share the items.
  }
  work();
  for (std::thread& helper : helpers) helper.join();
  if (failure) std::rethrow_exception(failure);
}

void parallelFor(size_t count, double item_cost, const std::function<void(size_t)>& item) {
  if (double(count) * item_cost < kMinParallelCost) {
    ThreadBudget serial(1);
    parallelFor(count, item);
    return;
  }
  parallelFor(count, item);
}

void parallelForBlocks(size_t count, size_t block, double element_cost,
                       const std::function<void(size_t, size_t, size_t)>& item) {
  parallelFor((count + block - 1) / block, element_cost * double(block), [&](size_t b) {
    const size_t begin = b * block;
    item(b, begin, std::min(count, begin + block));
  });
}

void copyOnThreads(const float* from, size_t n, float* to) {
  parallelForBlocks(n, kFloatsPerTask, 1,
                    [&](size_t, size_t begin, size_t end) { std::copy(from + begin, from + end, to + begin); });
}

void runBeside(const std::function<void()>& side, const std::function<void()>& main) {
  if (budget <= 1) {
    side();
    main();
    return;
  }
  std::exception_ptr side_failure;
  std::thread helper;
  try {
    helper = std::thread([&] {
      ThreadBudget one(1);
      try {
        side();
      } catch (...) {
        side_failure = std::current_exception();
      }
    });
  } catch (const std::system_error&) {
    side();  // no thread to be had
  }
  std::exception_ptr main_failure;
  try {
    main();
  } catch (...) {
    main_failure = std::current_exception();
  }
  if (helper.joinable()) helper.join();
  if (main_failure) std::rethrow_exception(main_failure);
  if (side_failure) std::rethrow_exception(side_failure);
}

}  // namespace animc
