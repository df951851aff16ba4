// Path survival (core/survival.h) decided inside the accumulate's launch, from the table that launch adds to: D10's
// cousin (docs/design/defects.md, "Broken survival"). A team that fuses its tracer and its accumulate, as caches that
// update while they trace do, reads each cell's variance while the frame's other samples are being added to it: what
// it reads depends on which of their adds came first, so the schedules explore it as they do the accumulate's races.
// hpsf's tracer decides before any pass of the frame, from the table the frame before left.
#ifndef HPSF_EMULATED_BROKEN_SURVIVAL_H
#define HPSF_EMULATED_BROKEN_SURVIVAL_H

#include <cstdint>
#include <map>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "core/previous_table_view.h"
#include "core/record.h"
#include "core/survival.h"

namespace hpsf {

// What the fused team traced: every path in full, the decision left to its accumulate.
struct SurvivalInPass {
  std::uint32_t seed = 0;  // the trace's, for each sample's draw (SurvivalDraw)
  // Per frame number, each record's light as traced on whatever the decision: the frame's records traced without
  // survival, the same paths (the draw is a dimension of its own).
  std::map<std::uint32_t, std::vector<glm::vec3>> traced;
};

// What the fused kernel (SurvivalDuringAccumulate, emulated/defect_injection.h) reads besides its own arguments, per
// record.
struct SurvivalInPassArgs {
  SurvivalParams params;
  std::span<const glm::vec3> traced;
  std::span<const float> draws;
  int fixed_point_bits = 0;  // the table's F and G, to read a cell's moments
  int square_bits = 0;
};

// The frame such a team would add had its decision read the table before the frame (`view`), as hpsf's tracer does:
// each record of `traced` with a vertex takes SurvivingContribution of its light, its draw and the view's p. The
// oracle the variant is judged against: where the launch reads a cell as the frame before left it, it adds these bits.
RecordBatch DecidedBeforeTheFrame(const RecordBatch& traced, const PreviousTableView& view, std::uint32_t seed);

// Each record's draw, 0 for one without a vertex.
std::vector<float> SurvivalDraws(const RecordBatch& batch, std::uint32_t seed);

}  // namespace hpsf

#endif  // HPSF_EMULATED_BROKEN_SURVIVAL_H
