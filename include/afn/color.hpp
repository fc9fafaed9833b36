// SPDX-License-Identifier: Apache-2.0
// afn_color: colour management with OpenColorIO 2.1, and display-referred pictures of AOVs
// (previews and contact sheets). Config resolution: an explicit path (--colorconfig), else $OCIO,
// else the project's own config (ocio/config.ocio, found in the build tree or the install prefix).
// Errors are thrown as afn::color::ColorError; nothing in here terminates the process.
#pragma once

// Symbols of the shared library (everything else in it is hidden).
#if defined(_WIN32)
#if defined(AFN_BUILDING_COLOR)
#define AFN_COLOR_API __declspec(dllexport)
#else
#define AFN_COLOR_API __declspec(dllimport)
#endif
#else
#define AFN_COLOR_API __attribute__((visibility("default")))
#endif

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace afn::color {

class AFN_COLOR_API ColorError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Which config file would be used for an explicit path ("" = none given), and why.
struct ConfigChoice {
    std::string path;
    std::string reason; ///< "--colorconfig" | "$OCIO" | "afn default"
};
AFN_COLOR_API ConfigChoice resolveConfig(const std::string& explicitPath = {});

/// A loaded config with cached processors. Thread-safe after construction.
class AFN_COLOR_API ColorManager {
public:
    /// Load the config chosen by resolveConfig(explicitPath); throws ColorError.
    explicit ColorManager(const std::string& explicitPath = {});
    ~ColorManager();
    ColorManager(const ColorManager&) = delete;
    ColorManager& operator=(const ColorManager&) = delete;

    const ConfigChoice& config() const;
    /// The scene-linear working space (role scene_linear).
    std::string workingSpace() const;
    std::vector<std::string> colorSpaces() const;
    std::vector<std::string> displays() const;
    std::vector<std::string> views(const std::string& display) const;
    std::string defaultDisplay() const;
    std::string defaultView(const std::string& display) const;
    /// True if the name (or alias or role) is a colour space of the config.
    bool hasColorSpace(const std::string& name) const;
    /// The colour space's own name for a name, alias or role ("" when unknown).
    std::string canonicalName(const std::string& name) const;
    /// A colour space's aliases (OCIO 2), e.g. ACEScg: acescg, lin_ap1, ...; empty when unknown.
    std::vector<std::string> aliases(const std::string& name) const;

    /// How `space` is recorded in an output's header (color_interop.cpp).
    struct FileTag {
        /// The Color Interop Forum id ("lin_ap1_scene", "lin_rec709_scene",
        /// "srgb_rec709_display", ...), "" when the space is not one of the known ones.
        std::string interopId;
        /// Red, green, blue and white CIE xy (the OpenEXR chromaticities attribute); empty when
        /// unknown or not an RGB space.
        std::vector<float> chromaticities;
    };
    FileTag fileTag(const std::string& space) const;
    /// The config's colour space for a Color Interop Forum id ("" when it has none).
    std::string spaceFromInteropId(const std::string& id) const;
    /// The colour space for 8-bit (bits 8) or 16-bit integer image files, as Nuke picks them in
    /// an OCIO config: role matte_paint for 8-bit, texture_paint for 16-bit, else a space named
    /// or aliased "sRGB", else role color_picking, else the working space.
    std::string integerFileSpace(int bits) const;

    /// Convert the first 3 channels of each pixel in place, from one colour space to another.
    /// `stride` = floats per pixel (>= 3); other channels are left untouched.
    void convert(float* pixels, int width, int height, int stride, const std::string& from,
        const std::string& to) const;
    /// Convert to the working space (no-op when `from` is it or empty).
    void toWorking(float* pixels, int width, int height, int stride, const std::string& from) const;
    /// Apply a display/view transform ("" = config defaults) from `from` ("" = working space).
    void toDisplay(float* pixels, int width, int height, int stride, const std::string& from,
        const std::string& display = {}, const std::string& view = {}) const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

/// One labelled tile of a contact sheet: display-referred RGB in [0, 1].
struct Tile {
    std::string label;
    int width = 0, height = 0;
    std::vector<float> rgb; ///< width*height*3
};

/// Turn a role's raw values into a viewable tile: colour-like roles through the display/view,
/// normals as n*0.5+0.5, depth and position normalised by their finite range, motion as a
/// direction/magnitude colour code. `kind` is a role name ("color", "albedo", "normal", ...),
/// "vector2" (any 2D vector, coded as motion) or anything else ("data": the first up-to-3
/// channels normalised by their joint finite range, one channel as grey). Motion and vector2
/// tiles get a direction legend (bottom-right disc, on tiles of 48 pixels or more) and
/// " (max length M)" on their label; data tiles get their range " [lo, hi]".
AFN_COLOR_API Tile makeTile(const ColorManager& cm, const std::string& kind,
    const std::string& label, int width, int height, int components, const float* pixels,
    const std::string& display = {}, const std::string& view = {});

/// Arrange tiles in a grid with their labels drawn above them (built-in bitmap font), on a dark
/// background; returns an RGB image of outWidth x outHeight in [0, 1].
/// Layout: cells as wide as the widest tile but at least kSheetMinCellWidth (so that a label of
/// small tiles stays legible) and as high as the highest tile; `columns` <= 0 = ceil(sqrt(tiles));
/// a gap of kSheetGap pixels around every cell; a label band of kSheetLabelBand pixels above each
/// tile. So outWidth = kSheetGap + columns * (cellW + kSheetGap) and
/// outHeight = kSheetGap + rows * (kSheetLabelBand + cellH + kSheetGap). A label is drawn in
/// whole glyphs inside its cell: wrapped after '.', ' ', ':' etc. onto at most kSheetLabelLines
/// lines, ending in "..." when it still does not fit. Throws ColorError on no tiles or a tile
/// whose rgb size does not match width*height*3.
AFN_COLOR_API std::vector<float> layoutContactSheet(
    const std::vector<Tile>& tiles, int columns, int& outWidth, int& outHeight);

constexpr int kSheetGap = 6; ///< pixels between and around contact-sheet cells
constexpr int kSheetLabelScale = 2; ///< label glyphs (5x9 font pixels) drawn at this scale
constexpr int kSheetLabelLines = 2; ///< lines of label text per tile at most
constexpr int kSheetLineHeight = 20; ///< pixels per label line: (9 font rows + 1 gap) * scale
constexpr int kSheetLabelBand = 46; ///< label band above each tile: 2 lines * 20 + 6 margin
constexpr int kSheetMinCellWidth = 192; ///< narrowest cell: 16 characters at scale 2
constexpr float kSheetBackground = 0.1f; ///< contact-sheet background grey (display-referred)

/// Box-filter a tile down so that it fits in maxWidth x maxHeight, keeping its aspect ratio;
/// returned unchanged when it already fits (useful before layoutContactSheet on large frames).
AFN_COLOR_API Tile fitTile(const Tile& tile, int maxWidth, int maxHeight);

} // namespace afn::color
