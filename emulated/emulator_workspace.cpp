#include "emulated/emulator_workspace.h"

#include <utility>

namespace hpsf {

void EmulatorWorkspace::Recycle(HashedRun&& run) {
  keys = std::exchange(run.keys, {});
  placements = std::exchange(run.placements, {});
  pixels = std::exchange(run.image.pixels, {});
  tags = std::exchange(run.table.tags, {});
  counts = std::exchange(run.table.counts, {});
  fixed_sums = std::exchange(run.table.fixed_sums, {});
  float_sums = std::exchange(run.table.float_sums, {});
}

}  // namespace hpsf
