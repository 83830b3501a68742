#include "status.hpp"

#include <cstdio>

namespace roadload::cli {
namespace {

thread_local MessageCapture* capture = nullptr;

}  // namespace

MessageCapture::MessageCapture() : outer_(capture) { capture = this; }

MessageCapture::~MessageCapture() { capture = outer_; }

void say(std::string_view command, std::string_view text) {
  if (capture != nullptr) {
    capture->add(text);
    return;
  }
  std::fprintf(stderr, "roadload%s%.*s: %.*s\n", command.empty() ? "" : " ", static_cast<int>(command.size()), command.data(),
               static_cast<int>(text.size()), text.data());
}

int failed(std::string_view command, const ParseError& e, int status) {
  say(command, e.to_string());
  return status;
}

int usage_error(std::string_view command, const std::string& message) {
  say(command, message + " (see --help)");
  return kExitUsage;
}

}  // namespace roadload::cli
