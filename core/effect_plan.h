// Effect planning (docs/design/tracer.md: the scene decides which effects run): each optional pass declares what
// in a scene and a run calls for it, and is skipped where nothing does. A pass is skipped only where it provably
// changes no output bit, so a skipped effect spends no time and forcing it (--force-effect NAME) gives the same
// image and table:
//   animation   the keyframes evaluated and the ray-tracing structure rebuilt for each frame: called for by a scene
//               with keyframes; a static scene is built once for the whole sequence.
//   temporal    the blend of a cell's history with the frame (--temporal ema|adaptive): called for by a frame with
//               history; the first frame of a sequence has none, so its blend is the identity.
//   level-seed  new cells seeded from another level (--level-change seed): called for by a frame with history and a
//               level range of more than one level; otherwise no cell's parent or children can be in the table.
//               (A hashed table looks a neighbour up by fingerprint, so a seed forced on one level could find an
//               aliased fingerprint where the exact map finds nothing: the plan's skip is the oracle's answer.)
//   eviction    the eviction pass after a frame (--eviction): called for from the frame `unseen` frames into the
//               sequence on (1 for strict and priority, N for stale:N); before it, every live cell was seen
//               recently enough. Each cell's last-seen frame is tracked whenever eviction is asked for.
//   neighbour-search  the resolve's search pass (--neighbour-search on): called for, frame by frame, by the pixels
//               with a record whose chosen cell holds fewer than --min-count samples, known only once the table is:
//               on Vulkan the resolve's first pass lists them and dispatches the search pass over them, with no
//               workgroup where there is none; the emulator and the reference search record by record. Forced, every
//               pixel goes through the search pass (Vulkan's first pass lists them all), which searches below the
//               threshold only.
//   transport   several filtered bounces (--transport on): each record takes its scattered vertex's light from the
//               table before the frame; called for from the second frame of a sequence on. The first frame's table
//               before it is empty, so every lookup misses: forced there, the pass looks up and finds nothing.
//   survival    variance-aware path survival (--survival, core/survival.h): the tracer reads each primary vertex's
//               cell in the table before the frame; called for from the second frame of a sequence on. The first
//               frame has no table before it: forced there, every lookup misses and every path survives with p = 1,
//               its records the same bits as without survival.
//   path-graph  adaptive path graphs (--path-graph, core/path_graph.h): the tracer reads the cell of each vertex along
//               a path in the table before the frame; called for from the second frame of a sequence on. Forced on
//               the first frame, every lookup misses and no path is cut: the records are path tracing's bits.
// An effect asked for but not called for by the scene (temporal forgetting on a static scene, say) still runs, since
// skipping it would change the result the user asked for; the plan says so in its reason.
#ifndef HPSF_CORE_EFFECT_PLAN_H
#define HPSF_CORE_EFFECT_PLAN_H

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace hpsf {

struct FilterConfig;

enum class Effect { kAnimation, kTemporal, kLevelSeed, kEviction, kNeighbourSearch, kTransport, kSurvival, kPathGraph };
inline constexpr std::array<Effect, 8> kEffects = {Effect::kAnimation, Effect::kTemporal,        Effect::kLevelSeed,
                                                   Effect::kEviction,  Effect::kNeighbourSearch, Effect::kTransport,
                                                   Effect::kSurvival,  Effect::kPathGraph};

// "animation", "temporal", "level-seed", "eviction", "neighbour-search", "transport", "survival", "path-graph"
std::string EffectName(Effect effect);

// Parses an effect's name; a ConfigError naming --force-effect otherwise.
Effect ParseEffect(const std::string& name);

// The effects --force-effect runs even where the plan skips them.
struct ForcedEffects {
  std::array<bool, kEffects.size()> forced{};

  bool Has(Effect effect) const { return forced[std::size_t(effect)]; }
  void Add(Effect effect) { forced[std::size_t(effect)] = true; }
  bool Any() const;
  std::string ToString() const;  // "none" or the names joined by ','
  bool operator==(const ForcedEffects&) const = default;
};

// The filter passes one frame runs. `index` is the frame's place in its sequence (0: the table was empty).
struct FrameEffects {
  bool temporal = false;
  bool level_seed = false;
  bool eviction = false;  // the eviction pass; last-seen frames are tracked whenever config.eviction is enabled
  bool search_every_pixel = false;  // the search pass resolves every pixel, not only those below the threshold
  bool transport = false;           // records take their scattered vertices' light from the table before the frame
  bool survival = false;            // the tracer reads the table before the frame for each path's survival
  bool path_graph = false;          // the tracer reads the table before the frame for each path's cut
};
FrameEffects PlanFrameEffects(const FilterConfig& config, std::uint32_t index);

// The place of a frame after the first whose place is not known (a filter called without its backend): planned as
// late as can be, so every pass that may act runs.
inline constexpr std::uint32_t kLaterFrame = 0xFFFFFFFFu;

// What the run knows of its scene.
struct SceneFacts {
  bool traced = true;     // false: the records come from a file, their scene unknown
  bool animated = false;  // the scene has keyframes
};

// One effect's decision for a whole sequence of `frames` frames, for the reports.
struct EffectDecision {
  Effect effect;
  bool asked = false;  // the options ask for it (animation: always asked)
  bool forced = false;
  std::uint32_t frames_run = 0;  // frames of the sequence on which it runs
  std::string reason;            // why it runs, or why it is skipped
};
std::vector<EffectDecision> PlanSequenceEffects(const FilterConfig& config, const SceneFacts& scene,
                                                std::uint32_t frames);

// Whether the scene's keyframes are evaluated and its ray-tracing structure rebuilt for each frame.
bool RebuildsScenePerFrame(const FilterConfig& config, const SceneFacts& scene);

}  // namespace hpsf

#endif  // HPSF_CORE_EFFECT_PLAN_H
