// Splits a loop over image rows into contiguous bands run on a few threads. The image tools are
// plain CPU code; this keeps a 1080p FLIP evaluation interactive without a thread pool.
#pragma once
#include <algorithm>
#include <thread>
#include <vector>

namespace bounce {

// Calls rowBand(begin, end) for disjoint bands covering [0, rows). Bands of fewer than
// `minRowsPerBand` rows are not worth a thread.
template <typename RowBand>
void parallelForRows(int rows, RowBand&& rowBand, int minRowsPerBand = 32) {
  const int hardware = int(std::max(1u, std::thread::hardware_concurrency()));
  const int bands = std::clamp(rows / std::max(1, minRowsPerBand), 1, hardware);
  if (bands == 1) {
    rowBand(0, rows);
    return;
  }
  std::vector<std::thread> workers;
  workers.reserve(bands - 1);
  for (int band = 1; band < bands; ++band) {
    workers.emplace_back([&, band] { rowBand(rows * band / bands, rows * (band + 1) / bands); });
  }
  rowBand(0, rows / bands);
  for (std::thread& worker : workers) worker.join();
}

}  // namespace bounce
