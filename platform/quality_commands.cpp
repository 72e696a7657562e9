#include "quality_commands.h"

namespace surfvp {

struct QualityCommands::State {};

QualityCommands::QualityCommands(CLI::App&) : state_(std::make_shared<State>()) {}

std::optional<int> QualityCommands::run() { return std::nullopt; }

}  // namespace surfvp
