#include "tools/hpsf/commands.h"

#include "tools/hpsf/check_command.h"
#include "tools/hpsf/crosscheck_command.h"
#include "tools/hpsf/device_command.h"
#include "tools/hpsf/diff_command.h"
#include "tools/hpsf/fuzz_command.h"
#include "tools/hpsf/golden_command.h"
#include "tools/hpsf/judge_command.h"
#include "tools/hpsf/reference_command.h"
#include "tools/hpsf/render_command.h"
#include "tools/hpsf/stats_command.h"
#include "tools/hpsf/sweep_command.h"

namespace hpsf {

void AddCommands(CLI::App& app, CommandContext& context) {
  app.require_subcommand(1);
  AddDeviceCommand(app, context);
  AddRenderCommand(app, context);
  AddReplayCommand(app, context);
  AddCrosscheckCommand(app, context);
  AddStatsCommand(app, context);
  AddDiffCommand(app, context);
  AddGoldenCommand(app, context);
  AddFuzzCommand(app, context);
  AddCheckCommand(app, context);
  AddJudgeCommand(app, context);
  AddReferenceCommand(app, context);
  AddSweepCommand(app, context);
}

}  // namespace hpsf
