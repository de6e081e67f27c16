#include "vdrive/scenario/junit_writer.hpp"

#include <stdexcept>
#include <string>
#include <utility>

#include <tinyxml2.h>
#include <fmt/format.h>

namespace vdrive::scenario {

void write_junit(const std::string& path, const std::vector<ScenarioResult>& results) {
  tinyxml2::XMLDocument doc;
  doc.InsertEndChild(doc.NewDeclaration());
  tinyxml2::XMLElement* suites = doc.NewElement("testsuites");
  doc.InsertEndChild(suites);
  int total = 0, failed = 0;
  for (const ScenarioResult& r : results) {
    tinyxml2::XMLElement* suite = suites->InsertNewChildElement("testsuite");
    suite->SetAttribute("name", r.name.c_str());
    suite->SetAttribute("file", r.file.c_str());
    int cases = 0, failures = 0;
    auto add = [&](const std::string& name, bool passed, const std::string& message, double seconds) {
      tinyxml2::XMLElement* tc = suite->InsertNewChildElement("testcase");
      tc->SetAttribute("classname", r.name.c_str());
      tc->SetAttribute("name", name.c_str());
      tc->SetAttribute("time", fmt::format("{:.6f}", seconds).c_str());
      if (!passed) {
        tinyxml2::XMLElement* f = tc->InsertNewChildElement("failure");
        f->SetAttribute("message", message.c_str());
        f->SetText(message.c_str());
        ++failures;
      } else if (!message.empty()) {
        tc->InsertNewChildElement("system-out")->SetText(message.c_str());
      }
      ++cases;
    };
    if (r.host_stalls > 0) {  // a real-time run the host stalled: say so beside the verdicts
      tinyxml2::XMLElement* props = suite->InsertNewChildElement("properties");
      for (const auto& [name, value] : {std::pair<const char*, std::string>{"host_stalls", std::to_string(r.host_stalls)},
                                        {"longest_host_stall_ns", std::to_string(r.longest_host_stall)}}) {
        tinyxml2::XMLElement* p = props->InsertNewChildElement("property");
        p->SetAttribute("name", name);
        p->SetAttribute("value", value.c_str());
      }
    }
    if (!r.error.empty()) add("run", false, r.error, 0.0);
    for (const ExpectationResult& e : r.expectations)
      add(e.name, e.passed, e.passed ? e.message : fmt::format("line {}: {}", e.line, e.message), static_cast<double>(e.time) / 1e9);
    suite->SetAttribute("tests", cases);
    suite->SetAttribute("failures", failures);
    suite->SetAttribute("errors", 0);
    suite->SetAttribute("time", fmt::format("{:.6f}", r.wall_seconds).c_str());
    total += cases;
    failed += failures;
  }
  suites->SetAttribute("tests", total);
  suites->SetAttribute("failures", failed);
  if (doc.SaveFile(path.c_str()) != tinyxml2::XML_SUCCESS) throw std::runtime_error(path + ": cannot write the JUnit report");
}

}  // namespace vdrive::scenario
