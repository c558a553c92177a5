#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>

#include "core/anim/track.h"
#include "core/anim/track_sampler.h"

using namespace animorph;

namespace {

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool sameBits(const glm::vec3& a, const glm::vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool sameBits(const glm::quat& a, const glm::quat& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

float randomValue(std::mt19937& rng, float) { return std::uniform_real_distribution<float>(-3.0f, 3.0f)(rng); }
glm::vec3 randomValue(std::mt19937& rng, const glm::vec3&) {
  std::uniform_real_distribution<float> d(-3.0f, 3.0f);
  return {d(rng), d(rng), d(rng)};
}
glm::quat randomValue(std::mt19937& rng, const glm::quat&) {
  std::uniform_real_distribution<float> d(-1.0f, 1.0f);
  return glm::normalize(glm::quat(d(rng), d(rng), d(rng), d(rng)));
}

// A track of `keys` keys at irregular times with every interpolation mode mixed in; some keys set
// their own derivatives.
template <class T>
Track<T> randomTrack(std::mt19937& rng, int keys, int degree) {
  Track<T> t;
  t.clearKeys();
  t.setDegree(degree);
  double time = std::uniform_real_distribution<double>(-1.0, 1.0)(rng);
  for (int i = 0; i < keys; ++i) {
    TrackKey<T> k;
    k.timeSec = time;
    k.value = randomValue(rng, T{});
    const int mode = int(rng() % 5);
    k.interp = mode == 0 ? KeyInterp::Constant : mode == 1 ? KeyInterp::Linear : KeyInterp::Hermite;
    if (rng() % 3 == 0) {
      k.userDerivatives = true;
      k.d1 = randomValue(rng, T{});
      k.d2 = randomValue(rng, T{});
    }
    t.setKey(k);
    time += std::uniform_real_distribution<double>(0.05, 1.3)(rng);
  }
  return t;
}

// Compares the sampler with Track::evaluate at times before, inside and after the key range, in
// order (the cursor moves forward), backwards, and at random (it jumps), and at the keys themselves.
template <class T>
void checkSameBits(const Track<T>& track) {
  TrackSampler<T> sampler(track);
  const auto& keys = track.keys();
  const double lo = keys.empty() ? -1.0 : keys.front().timeSec - 0.5;
  const double hi = keys.empty() ? 1.0 : keys.back().timeSec + 0.5;
  std::vector<double> times;
  for (int i = 0; i <= 400; ++i) times.push_back(lo + (hi - lo) * i / 400.0);
  for (int i = 400; i >= 0; --i) times.push_back(lo + (hi - lo) * i / 400.0 + 1e-4);
  std::mt19937 rng(7);
  for (int i = 0; i < 200; ++i) times.push_back(std::uniform_real_distribution<double>(lo, hi)(rng));
  for (const auto& k : keys) times.push_back(k.timeSec);
  int mismatches = 0;
  for (double t : times) mismatches += sameBits(sampler.sample(t), track.evaluate(t)) ? 0 : 1;
  CHECK(mismatches == 0);
}

}  // namespace

TEST_CASE("track sampler: float tracks of every interpolation mode sample bit for bit as Track::evaluate",
          "[track]") {
  std::mt19937 rng(11);
  for (int degree : {2, 3})
    for (int keys : {2, 3, 5, 12}) checkSameBits(randomTrack<float>(rng, keys, degree));
}

TEST_CASE("track sampler: vector tracks (cubic and quintic, automatic and user derivatives) match bit for bit",
          "[track]") {
  std::mt19937 rng(12);
  for (int degree : {2, 3})
    for (int keys : {2, 4, 9}) checkSameBits(randomTrack<glm::vec3>(rng, keys, degree));
}

TEST_CASE("track sampler: quaternion tracks (slerp and held segments) match bit for bit", "[track]") {
  std::mt19937 rng(13);
  for (int keys : {2, 3, 7}) checkSameBits(randomTrack<glm::quat>(rng, keys, 2));
}

TEST_CASE("track sampler: constant, empty and driven tracks", "[track]") {
  FloatTrack one(2.5f);
  TrackSampler<float> s1(one);
  CHECK(s1.constant());
  CHECK(s1.sample(-3.0) == 2.5f);
  CHECK(s1.sample(40.0) == 2.5f);
  QuatTrack none;
  none.clearKeys();
  TrackSampler<glm::quat> s0(none);
  CHECK(sameBits(s0.sample(1.0), none.evaluate(1.0)));
  Vec3Track driven;
  driven.setDriver([](double t) { return glm::vec3(float(t), float(2.0 * t), 1.0f); });
  TrackSampler<glm::vec3> sd(driven);
  CHECK_FALSE(sd.constant());
  CHECK(sd.sample(0.25) == glm::vec3(0.25f, 0.5f, 1.0f));
  FloatTrack two;
  two.clearKeys();
  two.setKey(0.0, 1.0f, KeyInterp::Linear);
  two.setKey(2.0, 3.0f, KeyInterp::Linear);
  TrackSampler<float> s2(two);
  CHECK_FALSE(s2.constant());
  CHECK(s2.sample(1.0) == 2.0f);  // a linear segment halfway
}
