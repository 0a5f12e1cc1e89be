// SPDX-License-Identifier: Apache-2.0
// How this machine runs the same work on two threads against one, for three kinds of work:
// arithmetic in registers, reads streaming through memory, and writes at random places in a
// buffer larger than the caches. Prints a JSON object of the three speed-ups (time of one
// thread doing both halves over the time of two threads doing one each), the median of five
// rounds. bench/bench_threads.py compiles and runs it, to say what the machine's speed-ups
// can be.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <thread>
#include <vector>

namespace {

volatile uint64_t sink;

void arithmetic(std::vector<uint32_t>&) {
  uint64_t x = 1, y = 3;
  for (uint64_t i = 0; i < 200000000; ++i) {
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    y = ((y ^ (x >> 17)) << 5) | (y >> 59);
  }
  sink = x ^ y;
}

void streamingReads(std::vector<uint32_t>& buffer) {
  uint64_t sum = 0;
  for (int pass = 0; pass < 4; ++pass)
    for (uint32_t v : buffer) sum += v;
  sink = sum;
}

void randomWrites(std::vector<uint32_t>& buffer) {
  const size_t span = buffer.size() / 8;  // 32 MiB
  uint64_t x = 1;
  for (size_t i = 0; i < 2 * span; ++i) {
    x = x * 6364136223846793005ull + 1;
    ++buffer[(x >> 33) % span];
  }
}

double seconds(const std::function<void()>& work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double speedUp(void (*work)(std::vector<uint32_t>&), std::vector<uint32_t>& a, std::vector<uint32_t>& b) {
  std::vector<double> ratios;
  for (int round = 0; round < 5; ++round) {
    const double one = seconds([&] {
      work(a);
      work(b);
    });
    const double two = seconds([&] {
      std::thread other([&] { work(b); });
      work(a);
      other.join();
    });
    ratios.push_back(one / two);
  }
  std::sort(ratios.begin(), ratios.end());
  return ratios[ratios.size() / 2];
}

}  // namespace

int main() {
  std::vector<uint32_t> a(size_t(1) << 26, 1), b(size_t(1) << 26, 1);  // 256 MiB each, touched
  std::printf("{\"arithmetic\": %.3f, \"streaming_reads\": %.3f, \"random_writes\": %.3f}\n",
              speedUp(arithmetic, a, b), speedUp(streamingReads, a, b), speedUp(randomWrites, a, b));
}
