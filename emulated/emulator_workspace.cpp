#include "emulated/emulator_workspace.h"

#include <utility>

namespace hpsf {

void EmulatorWorkspace::Recycle(HashedRun&& run) {
  keys = std::move(run.keys);
  placements = std::move(run.placements);
  pixels = std::move(run.image.pixels);
  tags = std::move(run.table.tags);
  counts = std::move(run.table.counts);
  fixed_sums = std::move(run.table.fixed_sums);
  float_sums = std::move(run.table.float_sums);
  run.keys = {};
  run.placements = {};
  run.image.pixels = {};
  run.table.tags = {};
  run.table.counts = {};
  run.table.fixed_sums = {};
  run.table.float_sums = {};
}

}  // namespace hpsf
