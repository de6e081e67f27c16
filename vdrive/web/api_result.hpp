#pragma once
// What an API call answers: an HTTP status and a JSON body ({"error": "..."} for a refusal).
#include <string>

#include <nlohmann/json.hpp>

namespace vdrive::web {

struct ApiResult {
  int status = 200;
  nlohmann::json body;
};

inline ApiResult api_error(int status, std::string message, nlohmann::json extra = nlohmann::json::object()) {
  extra["error"] = std::move(message);
  return {status, std::move(extra)};
}

}  // namespace vdrive::web
