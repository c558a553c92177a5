#include <catch2/catch.hpp>

#include <cmath>

#include "core/anim/track_json.h"
#include "core/anim/track.h"

using namespace animorph;
using Catch::Matchers::Contains;

namespace {

// Central-difference derivative of evaluate().
template <class T>
T numericDerivative(const Track<T>& t, double x, double h = 1e-3) {
  return (t.evaluate(x + h) - t.evaluate(x - h)) / float(2.0 * h);
}

}  // namespace

TEST_CASE("cubic Hermite (n = 2) reproduces key values and user derivatives", "[track]") {
  FloatTrack t;
  t.clearKeys();
  const double times[] = {0.0, 0.7, 1.5, 3.0};
  const float values[] = {1.0f, -2.0f, 0.5f, 4.0f};
  const float slopes[] = {0.0f, 3.0f, -1.0f, 2.0f};
  for (int i = 0; i < 4; ++i) {
    TrackKey<float> k;
    k.timeSec = times[i];
    k.value = values[i];
    k.userDerivatives = true;
    k.d1 = slopes[i];
    t.setKey(k);
  }
  for (int i = 0; i < 3; ++i) {  // the last key holds; its left derivative is checked through i = 2's segment
    CHECK(t.evaluate(times[i]) == Approx(values[i]).margin(1e-6));
    CHECK(t.derivative(times[i]) == Approx(slopes[i]).margin(1e-4));
    // Approaching the next key from the left gives its value and slope.
    CHECK(t.evaluate(times[i + 1] - 1e-6) == Approx(values[i + 1]).margin(1e-4));
    CHECK(t.derivative(times[i + 1] - 1e-6) == Approx(slopes[i + 1]).margin(1e-3));
  }
  CHECK(t.evaluate(10.0) == 4.0f);  // holds after the last key
  CHECK(t.evaluate(-1.0) == 1.0f);
  for (double x = 0.05; x < 3.0; x += 0.1) CHECK(t.derivative(x) == Approx(numericDerivative(t, x)).margin(2e-3));
}

TEST_CASE("quintic Hermite (n = 3) reproduces values, velocities and accelerations", "[track]") {
  Vec3Track t;
  t.clearKeys();
  t.setDegree(3);
  TrackKey<glm::vec3> a, b;
  a.timeSec = 0.0;
  a.value = {0, 1, 2};
  a.userDerivatives = true;
  a.d1 = {1, 0, -1};
  a.d2 = {0.5f, -2, 0};
  b.timeSec = 2.0;
  b.value = {3, -1, 0};
  b.userDerivatives = true;
  b.d1 = {0, 2, 1};
  b.d2 = {-1, 0, 3};
  t.setKey(a);
  t.setKey(b);
  auto near = [](glm::vec3 x, glm::vec3 y, float tol) { return glm::length(x - y) < tol; };
  CHECK(near(t.evaluate(0.0), a.value, 1e-6f));
  CHECK(near(t.derivative(0.0, 1), a.d1, 1e-5f));
  CHECK(near(t.derivative(0.0, 2), a.d2, 1e-4f));
  double e = 2.0 - 1e-7;
  CHECK(near(t.evaluate(e), b.value, 1e-4f));
  CHECK(near(t.derivative(e, 1), b.d1, 1e-4f));
  CHECK(near(t.derivative(e, 2), b.d2, 1e-3f));
  for (double x = 0.1; x < 1.95; x += 0.17) {
    CHECK(near(t.derivative(x), numericDerivative(t, x), 2e-3f));
    glm::vec3 second = (t.evaluate(x + 1e-2) - 2.0f * t.evaluate(x) + t.evaluate(x - 1e-2)) / 1e-4f;
    CHECK(near(t.derivative(x, 2), second, 5e-2f));
  }
}

TEST_CASE("automatic tangents are Catmull-Rom, constant and linear keys", "[track]") {
  FloatTrack t;
  t.clearKeys();
  t.setKey(0.0, 0.0f);
  t.setKey(1.0, 2.0f);
  t.setKey(3.0, 3.0f);
  CHECK(t.derivative(1.0) == Approx((3.0 - 0.0) / 3.0).margin(1e-5));
  CHECK(t.derivative(0.0) == Approx(2.0).margin(1e-5));
  FloatTrack c;
  c.clearKeys();
  c.setKey(0.0, 1.0f, KeyInterp::Constant);
  c.setKey(1.0, 5.0f, KeyInterp::Linear);
  c.setKey(2.0, 7.0f);
  CHECK(c.evaluate(0.99) == 1.0f);
  CHECK(c.evaluate(1.5) == Approx(6.0f));
  CHECK(c.derivative(1.5) == Approx(2.0f));
  CHECK(c.derivative(0.5) == 0.0f);
  CHECK(FloatTrack(3.5f).isConstant());
  CHECK(FloatTrack(3.5f).evaluate(100.0) == 3.5f);
}

TEST_CASE("quaternion tracks slerp along the short arc and stay unit length", "[track]") {
  QuatTrack t;
  t.clearKeys();
  glm::quat q0(1, 0, 0, 0);
  glm::quat q1 = glm::angleAxis(glm::radians(170.0f), glm::vec3(0, 0, 1));
  t.setKey(0.0, q0);
  t.setKey(1.0, -q1);  // same rotation, opposite hemisphere: must still take the 170 degree arc
  for (double x = 0.0; x <= 1.0; x += 0.05) CHECK(glm::length(t.evaluate(x)) == Approx(1.0f).margin(1e-5));
  glm::quat mid = t.evaluate(0.5);
  float angle = 2.0f * std::acos(std::min(1.0f, std::abs(mid.w)));
  CHECK(glm::degrees(angle) == Approx(85.0f).margin(0.05));
  glm::vec3 axis = glm::normalize(glm::vec3(mid.x, mid.y, mid.z)) * (mid.w < 0 ? -1.0f : 1.0f);
  CHECK(axis.z == Approx(1.0f).margin(1e-4));
  // Angular speed is constant: |dq/dt| = angle / 2 per unit time.
  for (double x = 0.1; x < 0.95; x += 0.2)
    CHECK(glm::length(t.derivative(x)) == Approx(glm::radians(170.0f) / 2.0f).margin(1e-3));
}

TEST_CASE("a track driven by a callback", "[track]") {
  FloatTrack t;
  t.setDriver([](double x) { return float(std::sin(x)); });
  CHECK(t.driven());
  CHECK(t.evaluate(0.5) == Approx(std::sin(0.5)));
  CHECK(t.derivative(0.5) == Approx(std::cos(0.5)).margin(1e-3));
  t.setDriver({});
  CHECK_FALSE(t.driven());
}

TEST_CASE("track JSON round trip and errors", "[track]") {
  Vec3Track v;
  v.setDegree(3);
  v.setKey(0.0, glm::vec3(1, 2, 3), KeyInterp::Linear);
  TrackKey<glm::vec3> k;
  k.timeSec = 2.0;
  k.value = {4, 5, 6};
  k.userDerivatives = true;
  k.d1 = {1, 0, 0};
  k.d2 = {0, 1, 0};
  v.setKey(k);
  auto back = vec3TrackFromJson(trackToJson(v), "v");
  REQUIRE(back.ok());
  CHECK(back->degree() == 3);
  REQUIRE(back->keys().size() == 2);
  for (double x : {0.0, 0.3, 1.0, 1.7, 2.0}) CHECK(glm::length(back->evaluate(x) - v.evaluate(x)) < 1e-6f);
  CHECK(trackToJson(FloatTrack(2.5f)) == nlohmann::json(2.5));
  auto q = quatTrackFromJson(nlohmann::json::array({0, 0, 1, 1}), "q");
  REQUIRE(q.ok());
  CHECK(glm::length(q->evaluate(0.0)) == Approx(1.0f));

  nlohmann::json nan = nlohmann::json::object({{"keys", {{{"t", 0}, {"v", std::nan("")}}}}});
  auto bad = floatTrackFromJson(nan, "node 3: parameter 'radius'");
  REQUIRE_FALSE(bad.ok());
  CHECK_THAT(bad.error(), Contains("node 3") && Contains("NaN"));
  nlohmann::json unsorted = nlohmann::json::parse(R"({"keys": [{"t": 1, "v": 0}, {"t": 0.5, "v": 1}]})");
  CHECK_THAT(floatTrackFromJson(unsorted, "x").error(), Contains("increase"));
  CHECK_THAT(vec3TrackFromJson(nlohmann::json::array({1, 2}), "x").error(), Contains("[x, y, z]"));
}
