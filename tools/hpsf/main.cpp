// hpsf: a verification harness for hashed path space filtering. Exit codes: 0 pass, 1 warn, 2 a failed check,
// 3 bad input (a bad option or file, or no usable Vulkan device), 4 hpsf failed internally (an exception escaped:
// never an abort, so a gate tells hpsf's own failure from a verdict).
#include <exception>
#include <iostream>

#include <CLI/CLI.hpp>

#include "core/error.h"
#include "core/read_back_check.h"
#include "emulated/simt/kernel_fault.h"
#include "tools/hpsf/commands.h"
#include "tools/hpsf/version.h"
#include "vulkan/vulkan_device.h"

int main(int argc, char** argv) {
  CLI::App app(hpsf::kHpsfDescription, "hpsf");
  hpsf::CommandContext context;
  app.set_version_flag("--version", std::string("hpsf ") + hpsf::kHpsfVersion);
  hpsf::AddCommands(app, context);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? hpsf::kExitOk : hpsf::kExitBadInput;
  } catch (const hpsf::InputError& e) {
    std::cerr << "hpsf: " << e.what() << "\n";
    return hpsf::kExitBadInput;
  } catch (const hpsf::VulkanUnavailable& e) {
    std::cerr << "hpsf: " << e.what() << "\n";
    return hpsf::kExitBadInput;
  } catch (const hpsf::simt::KernelFault& e) {  // a broken kernel (--inject-defect): a failed check, no output
    std::cerr << "hpsf: kernel fault: " << e.what() << "\n";
    return hpsf::kExitCheckFailed;
  } catch (const hpsf::CheckFailed& e) {
    std::cerr << "hpsf: check failed: " << e.what() << "\n";
    return hpsf::kExitCheckFailed;
  } catch (const hpsf::ShaderOutputError& e) {  // a shader left words the host cannot use: a failed check
    std::cerr << "hpsf: " << e.what() << "\n";
    return hpsf::kExitCheckFailed;
  } catch (const std::exception& e) {
    std::cerr << "hpsf: internal error (exit " << hpsf::kExitInternalError << "): " << e.what() << "\n";
    return hpsf::kExitInternalError;
  } catch (...) {
    std::cerr << "hpsf: internal error (exit " << hpsf::kExitInternalError << "): an unknown exception\n";
    return hpsf::kExitInternalError;
  }
  return context.exit_code;
}
