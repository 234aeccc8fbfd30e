// Runtime policies: the performance log records copies and launches, the info sink gets padding,
// alignment and copy messages, and each facet is on or off alone.
#include <cstddef>
#include <sstream>
#include <string>
#include <vector>

#include "catch_compat.hpp"
#include "gpusolve/containers.hpp"

using namespace gpusolve;

namespace {
// Collects the messages of one test and restores the previous sink afterwards.
struct CapturedInfo {
  std::vector<std::string> lines;
  runtime::InfoSink previous;
  CapturedInfo() {
    previous = runtime::set_info_sink([this](const std::string& m) { lines.push_back(m); });
  }
  ~CapturedInfo() { runtime::set_info_sink(previous); }
  bool any_contains(const std::string& s) const {
    for (const auto& l : lines)
      if (l.find(s) != std::string::npos) return true;
    return false;
  }
};
}  // namespace

TEST_CASE("the performance policy records bytes and times of copies", "[policy][runtime]") {
  runtime::performance_log().clear();
  VectorD2<double, runtime_policy_is<runtime::PerformancePolicy>> a(33, 3);
  a.fill(1.0);
  VectorD2<double, layout_is<layout::NoPadding>> b(33, 3);
  b = a;  // the source's policy asks for the record
  VectorD2<double> c(33, 3), d(33, 3);
  d = c;  // neither side asks: no record
  const auto copies = runtime::performance_log().copies();
  REQUIRE(copies.size() == 1);
  CHECK(copies[0].bytes == 33 * 3 * sizeof(double));
  CHECK(copies[0].from == "host");
  CHECK(copies[0].to == "host");
  CHECK(copies[0].seconds >= 0.0);
  CHECK_FALSE(copies[0].async);
  copy_async(b, a, stream_t{});
  REQUIRE(runtime::performance_log().copies().size() == 2);
  CHECK(runtime::performance_log().copies()[1].async);
}

TEST_CASE("measured_launch records launches under a performance policy only", "[policy][runtime]") {
  runtime::performance_log().clear();
  VectorD1<int> v(100);
  auto body = [p = v.data()](std::size_t i) { p[i] = static_cast<int>(i); };
  runtime::measured_launch<runtime::PerformancePolicy>("iota", device::cpu{}, v.size(), body);
  runtime::measured_launch<runtime::InfoPolicy>("not recorded", device::cpu{}, v.size(), body);
  const auto launches = runtime::performance_log().launches();
  REQUIRE(launches.size() == 1);
  CHECK(launches[0].label == "iota");
  CHECK(launches[0].device == "cpu");
  CHECK(launches[0].n == 100);
  CHECK(v(99) == 99);
}

TEST_CASE("the info policy reports padding, alignment and copies to the user's sink", "[policy][runtime]") {
  CapturedInfo info;
  runtime::performance_log().clear();
  VectorD2<float, runtime_policy_is<runtime::InfoPolicy>> a(33, 3);
  REQUIRE(info.lines.size() == 1);
  CHECK(info.any_contains("logical 33 x 3"));
  CHECK(info.any_contains("padded 64 x 3"));
  CHECK(info.any_contains("row pitch 256 bytes"));
  CHECK(info.any_contains("aligned to"));
  VectorD2<float, layout_is<layout::NoPadding>> b(33, 3);
  b = a;
  REQUIRE(info.lines.size() == 2);
  CHECK(info.any_contains("copy host -> host"));
  CHECK(info.any_contains("pitched rows"));
  CHECK(runtime::performance_log().copies().empty());  // info alone records nothing
  VectorD2<float> quiet(5, 5);
  CHECK(info.lines.size() == 2);
}

TEST_CASE("an ostream can be the info sink, and both facets work together", "[policy][runtime]") {
  std::ostringstream os;
  const auto previous = runtime::set_info_sink(os);
  runtime::performance_log().clear();
  VectorD1<int, runtime_policy_is<runtime::FullPolicy>> a(7);
  VectorD1<int, runtime_policy_is<runtime::FullPolicy>> b(a);
  runtime::set_info_sink(previous);
  CHECK(os.str().find("VectorD1 on cpu (host memory): logical 7") != std::string::npos);
  CHECK(os.str().find("copy host -> host") != std::string::npos);
  CHECK(runtime::performance_log().copies().size() == 1);
  STATIC_REQUIRE(runtime::either<runtime::InfoPolicy, runtime::PerformancePolicy>::performance);
  STATIC_REQUIRE(runtime::either<runtime::InfoPolicy, runtime::PerformancePolicy>::info);
  STATIC_REQUIRE(!runtime::either<runtime::Off, runtime::InfoPolicy>::performance);
}
