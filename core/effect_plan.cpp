#include "core/effect_plan.h"

#include <algorithm>

#include "core/error.h"
#include "core/filter_config.h"

namespace hpsf {
namespace {

// The first frame index (within a sequence) on which the eviction pass can evict anything: a cell is evicted by age
// once unseen for `unseen_frames`, and by priority only if the frame did not touch it, which needs a frame before.
std::uint32_t FirstEvictingFrame(const Eviction& eviction) {
  return eviction.by_priority() ? 1u : std::max(eviction.unseen_frames, 1u);
}

// How many of a sequence's frames run the pass `pass` of their plan.
std::uint32_t FramesRunning(const FilterConfig& config, std::uint32_t frames, bool FrameEffects::*pass) {
  std::uint32_t running = 0;
  for (std::uint32_t k = 0; k < frames; ++k) running += PlanFrameEffects(config, k).*pass;
  return running;
}

std::string Frames(std::uint32_t n) { return std::to_string(n) + (n == 1 ? " frame" : " frames"); }

EffectDecision DecideAnimation(const FilterConfig& config, const SceneFacts& scene, std::uint32_t frames) {
  EffectDecision d{Effect::kAnimation, scene.traced, config.forced.Has(Effect::kAnimation), 0, ""};
  if (!scene.traced) {
    d.reason = "the records come from a file: nothing is traced";
  } else if (scene.animated) {
    d.frames_run = frames;
    d.reason = "the scene has keyframes: evaluated and rebuilt for each frame";
  } else if (d.forced) {
    d.frames_run = frames;
    d.reason = "forced: the static scene rebuilt for each frame";
  } else {
    d.reason = "the scene has no keyframes: built once for " + Frames(frames);
  }
  return d;
}

EffectDecision DecideTemporal(const FilterConfig& config, const SceneFacts& scene, std::uint32_t frames) {
  EffectDecision d{Effect::kTemporal, config.temporal.blends(), config.forced.Has(Effect::kTemporal), 0, ""};
  if (!d.asked) {
    d.reason = "--temporal integrate: the table's sums are the blend";
    return d;
  }
  d.frames_run = FramesRunning(config, frames, &FrameEffects::temporal);
  if (d.forced && frames == 1) {
    d.reason = "forced: blends the first frame with an empty history";
  } else if (frames == 1) {
    d.reason = "a single frame has no history to blend";
  } else if (scene.traced && !scene.animated) {
    d.reason =
        "runs as asked on frames after the first, though the scene is static: its history never goes stale, "
        "so forgetting it only adds variance";
  } else {
    d.reason = "frames after the first blend their history";
  }
  return d;
}

EffectDecision DecideLevelSeed(const FilterConfig& config, const SceneFacts& scene, std::uint32_t frames) {
  EffectDecision d{Effect::kLevelSeed, config.level_seed.enabled, config.forced.Has(Effect::kLevelSeed), 0, ""};
  if (!d.asked) {
    d.reason = "--level-change none";
    return d;
  }
  d.frames_run = FramesRunning(config, frames, &FrameEffects::level_seed);
  const bool one_level = config.level_min == config.level_max;
  const std::string skipped = one_level ? "a single level in use (--level-min = --level-max): no cell has a parent "
                                          "or child in the table"
                                        : "a single frame has no table to seed from";
  if (d.frames_run == 0) {
    d.reason = skipped;
  } else if (d.forced && (one_level || frames == 1)) {
    d.reason = "forced, though " + skipped;
  } else if (scene.traced && !scene.animated) {
    d.reason =
        "runs as asked on frames after the first, though the scene is static: a location's level never "
        "changes";
  } else {
    d.reason = "frames after the first seed a cell new at another level from its parent or children";
  }
  return d;
}

EffectDecision DecideEviction(const FilterConfig& config, const SceneFacts& scene, std::uint32_t frames) {
  EffectDecision d{Effect::kEviction, config.eviction.enabled(), config.forced.Has(Effect::kEviction), 0, ""};
  if (!d.asked) {
    d.reason = "--eviction none";
    return d;
  }
  d.frames_run = FramesRunning(config, frames, &FrameEffects::eviction);
  const std::uint32_t first = FirstEvictingFrame(config.eviction);
  const std::string none_evictable = "no cell can be evicted before frame " + std::to_string(first) +
                                     " of the sequence (" + config.eviction.ToString() + ")";
  if (frames <= first && !d.forced) {
    d.reason = Frames(frames) + ": " + none_evictable;
  } else if (d.forced) {
    d.reason = "forced on every frame, though " + none_evictable;
  } else if (scene.traced && !scene.animated) {
    d.reason = "runs as asked from frame " + std::to_string(first) +
               " on, though the scene is static: its cells never go stale, so evicting them loses samples";
  } else {
    d.reason = "runs from frame " + std::to_string(first) + " of the sequence on";
  }
  return d;
}

EffectDecision DecideNeighbourSearch(const FilterConfig& config, std::uint32_t frames) {
  EffectDecision d{Effect::kNeighbourSearch, config.neighbour_search, config.forced.Has(Effect::kNeighbourSearch), 0,
                   ""};
  if (!d.asked) {
    d.reason = "--neighbour-search off";
    return d;
  }
  d.frames_run = frames;
  d.reason = d.forced ? "forced: every pixel goes through the search pass, which searches only where a chosen cell "
                        "holds fewer than " +
                            std::to_string(config.min_count) + " samples"
                      : "runs on the pixels with a record whose chosen cell holds fewer than " +
                            std::to_string(config.min_count) + " samples, known frame by frame once the table is";
  return d;
}

// An effect that reads the table before the frame, so runs from frame 1 of a sequence on (frame 0 has none, and
// forced there reads nothing): the transport, survival and path graphs.
EffectDecision DecideFromFrameOne(const FilterConfig& config, std::uint32_t frames, Effect effect, bool asked,
                                  bool FrameEffects::*member, const std::string& off, const std::string& empty,
                                  const std::string& runs) {
  EffectDecision d{effect, asked, config.forced.Has(effect), 0, ""};
  if (!d.asked) {
    d.reason = off;
    return d;
  }
  d.frames_run = FramesRunning(config, frames, member);
  if (d.forced) {
    d.reason = "forced on every frame, though " + empty;
  } else if (frames == 1) {
    d.reason = "a single frame: " + empty;
  } else {
    d.reason = "runs from frame 1 of the sequence on: " + runs;
  }
  return d;
}

EffectDecision DecideTransport(const FilterConfig& config, std::uint32_t frames) {
  return DecideFromFrameOne(config, frames, Effect::kTransport, config.transport, &FrameEffects::transport,
                            "--transport off", "the first frame's table before it is empty: every lookup misses",
                            "each record takes its scattered vertex's light from the table before the frame");
}

EffectDecision DecideSurvival(const FilterConfig& config, std::uint32_t frames) {
  return DecideFromFrameOne(config, frames, Effect::kSurvival, config.survival.enabled(), &FrameEffects::survival,
                            "--survival off", "the first frame has no table before it: every path survives",
                            "each path survives its primary vertex by its cell's variance in the table before the "
                            "frame");
}

EffectDecision DecidePathGraph(const FilterConfig& config, std::uint32_t frames) {
  return DecideFromFrameOne(config, frames, Effect::kPathGraph, config.path_graph.enabled, &FrameEffects::path_graph,
                            "--path-graph off", "the first frame has no table before it: no path is cut",
                            "each path is cut where the variance of its vertices' cells in the table before the "
                            "frame passes the bound");
}

}  // namespace

std::string EffectName(Effect effect) {
  switch (effect) {
    case Effect::kAnimation:
      return "animation";
    case Effect::kTemporal:
      return "temporal";
    case Effect::kLevelSeed:
      return "level-seed";
    case Effect::kEviction:
      return "eviction";
    case Effect::kNeighbourSearch:
      return "neighbour-search";
    case Effect::kTransport:
      return "transport";
    case Effect::kSurvival:
      return "survival";
    case Effect::kPathGraph:
      return "path-graph";
  }
  return "?";
}

Effect ParseEffect(const std::string& name) {
  for (Effect effect : kEffects) {
    if (EffectName(effect) == name) return effect;
  }
  throw ConfigError("--force-effect", "is not an effect: '" + name +
                                          "' (animation, temporal, level-seed, eviction, neighbour-search, transport, "
                                          "survival, path-graph)");
}

bool ForcedEffects::Any() const { return std::find(forced.begin(), forced.end(), true) != forced.end(); }

std::string ForcedEffects::ToString() const {
  std::string text;
  for (Effect effect : kEffects) {
    if (Has(effect)) text += (text.empty() ? "" : ",") + EffectName(effect);
  }
  return text.empty() ? "none" : text;
}

FrameEffects PlanFrameEffects(const FilterConfig& config, std::uint32_t index) {
  const ForcedEffects& forced = config.forced;
  FrameEffects e;
  e.temporal = config.temporal.blends() && (index > 0 || forced.Has(Effect::kTemporal));
  e.level_seed = config.level_seed.enabled &&
                 ((index > 0 && config.level_min < config.level_max) || forced.Has(Effect::kLevelSeed));
  e.eviction =
      config.eviction.enabled() && (index >= FirstEvictingFrame(config.eviction) || forced.Has(Effect::kEviction));
  e.search_every_pixel = config.neighbour_search && forced.Has(Effect::kNeighbourSearch);
  // The first frame's table before it is empty: every lookup misses.
  e.transport = config.transport && (index > 0 || forced.Has(Effect::kTransport));
  // Likewise: a first frame's survival reads no table, and every path survives with p = 1.
  e.survival = config.survival.enabled() && (index > 0 || forced.Has(Effect::kSurvival));
  // And no path is cut.
  e.path_graph = config.path_graph.enabled && (index > 0 || forced.Has(Effect::kPathGraph));
  return e;
}

std::vector<EffectDecision> PlanSequenceEffects(const FilterConfig& config, const SceneFacts& scene,
                                                std::uint32_t frames) {
  return {DecideAnimation(config, scene, frames), DecideTemporal(config, scene, frames),
          DecideLevelSeed(config, scene, frames), DecideEviction(config, scene, frames),
          DecideNeighbourSearch(config, frames),  DecideTransport(config, frames),
          DecideSurvival(config, frames),         DecidePathGraph(config, frames)};
}

bool RebuildsScenePerFrame(const FilterConfig& config, const SceneFacts& scene) {
  return scene.animated || config.forced.Has(Effect::kAnimation);
}

}  // namespace hpsf
