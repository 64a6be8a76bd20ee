#include "magFoam/Log.hpp"

#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/stdout_sinks.h>

namespace mag::log {

namespace {
// "%*": nothing for info lines (they read like OpenFOAM logs), "Warning: " /
// "Error: " / "debug: " otherwise, so problems stand out in log files.
class LevelPrefix : public spdlog::custom_flag_formatter {
public:
    void format(const spdlog::details::log_msg& msg, const std::tm&, spdlog::memory_buf_t& dest) override {
        const char* text = "";
        switch (msg.level) {
        case spdlog::level::warn: text = "Warning: "; break;
        case spdlog::level::err:
        case spdlog::level::critical: text = "Error: "; break;
        case spdlog::level::debug:
        case spdlog::level::trace: text = "debug: "; break;
        default: break;
        }
        dest.append(text, text + std::char_traits<char>::length(text));
    }
    std::unique_ptr<custom_flag_formatter> clone() const override { return std::make_unique<LevelPrefix>(); }
};
} // namespace

void init(const std::string& level) {
    auto logger = spdlog::get("magFoam");
    if (!logger) {
        logger = spdlog::stdout_logger_mt("magFoam");
        auto formatter = std::make_unique<spdlog::pattern_formatter>();
        formatter->add_flag<LevelPrefix>('*').set_pattern("%*%v");
        logger->set_formatter(std::move(formatter));
        spdlog::set_default_logger(logger);
    }
    spdlog::set_level(spdlog::level::from_str(level));
}

} // namespace mag::log
