#include "emulated/cuckoo_kernels.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <memory>
#include <utility>

namespace hpsf {

simt::KernelTask CuckooInsertKernel(simt::ThreadContext& ctx, const CuckooArgs& args) {
  std::uint32_t key = args.keys[ctx.Thread()];
  std::uint32_t slot = shared::CuckooSlot(args.params, 0, key);
  for (std::uint32_t chain = 0;; ++chain) {
    std::uint32_t out;
    if (args.defect == CuckooInsertDefect::kLoadThenStore) {
      out = std::uint32_t(co_await ctx.Load(args.slots, slot));
      co_await ctx.Store(args.slots, slot, key);
    } else {
      out = std::uint32_t(co_await ctx.AtomicExchange(args.slots, slot, key));
    }
    if (out == shared::kCuckooEmpty) co_return;
    if (chain == args.max_chain) {
      if (args.defect != CuckooInsertDefect::kDropAtLimit) co_await ctx.AtomicAdd(args.failed, 0, 1);
      co_return;
    }
    key = out;
    slot = shared::CuckooNextSlot(args.params, key, slot);
  }
}

CuckooBuild BuildCuckooMapEmulated(std::span<const std::uint32_t> keys, const CuckooBuildOptions& build_options,
                                   const EmulatorOptions& options, CuckooInsertDefect defect) {
  options.Validate();
  const std::uint32_t max_chain = CuckooMaxChain(keys.size(), build_options);
  CuckooBuild build;
  double space = build_options.space;
  for (build.attempts = 1; build.attempts <= build_options.max_attempts;
       ++build.attempts, space *= build_options.growth) {
    const std::uint32_t size = CuckooSlots(keys.size(), space);
    simt::DeviceMemory memory;
    CuckooArgs args;
    args.params =
        shared::CuckooFunctions(build_options.seed, build_options.level, build.attempts, size, build_options.functions);
    args.keys = keys;
    args.max_chain = max_chain;
    args.slots = memory.Allocate32("cuckoo_slots", size);
    args.failed = memory.Allocate64("cuckoo_failed", 1);
    args.defect = defect;
    std::fill(memory.Words32(args.slots).begin(), memory.Words32(args.slots).end(), shared::kCuckooEmpty);
    const simt::Kernel kernel = [&](simt::ThreadContext& ctx) { return CuckooInsertKernel(ctx, args); };
    const auto threads = static_cast<std::uint32_t>(keys.size());
    if (options.mode == simt::Mode::kFast) {
      simt::LaunchFast(memory, threads, kernel, options.threads);
    } else {
      const std::uint32_t warps = (threads + options.warp_size - 1) / options.warp_size;
      std::unique_ptr<simt::Schedule> parsed;
      if (!options.schedule_instance) parsed = simt::MakeSchedule(options.schedule, warps, std::uint64_t(warps) * 8);
      simt::LaunchFaithful(memory, threads, options.warp_size, kernel,
                           options.schedule_instance ? *options.schedule_instance : *parsed);
    }
    const bool failed = std::as_const(memory).Words64(args.failed)[0] != 0;
    build.map.params = args.params;
    build.map.slots = memory.TakeWords32(args.slots);
    if (!failed) {
      build.built = true;
      return build;
    }
  }
  build.attempts = build_options.max_attempts;
  return build;
}

}  // namespace hpsf
