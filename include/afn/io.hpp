// SPDX-License-Identifier: Apache-2.0
// afn_io: reading renderer EXRs (AOV roles, space tags, sequences, the BMFR dataset layout) and
// writing images atomically. Built on OpenImageIO; separate from the compute library (libafn does
// no file I/O). Errors are thrown as afn::io::IoError carrying the file they concern; nothing in
// here terminates the process.
#pragma once

#include "afn/afn.h"

// Symbols of the shared library (everything else in it is hidden).
#if defined(_WIN32)
#if defined(AFN_BUILDING_IO)
#define AFN_IO_API __declspec(dllexport)
#else
#define AFN_IO_API __declspec(dllimport)
#endif
#else
#define AFN_IO_API __attribute__((visibility("default")))
#endif

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace afn::io {

/// An I/O failure: message plus the file it concerns (may be empty).
class AFN_IO_API IoError : public std::runtime_error {
public:
    IoError(const std::string& message, std::string file = {})
        : std::runtime_error(message)
        , m_file(std::move(file))
    {
    }
    const std::string& file() const { return m_file; }

private:
    std::string m_file;
};

// ---- AOV roles ----------------------------------------------------------------------------------

/// What a group of channels means to a denoiser. Names: color, albedo, normal, depth, position,
/// motion, alpha, variance, specular.
enum class Role { Color, Albedo, Normal, Depth, Position, Motion, Alpha, Variance, Specular };
constexpr int kNumRoles = 9;

/// Lower-case role name ("color", ...).
AFN_IO_API const char* roleName(Role role);
/// Role from its name; nullopt if unknown.
AFN_IO_API std::optional<Role> roleFromName(const std::string& name);
/// Number of components a role has (color 3, albedo 3, normal 3, depth 1, position 3, motion 2,
/// alpha 1, variance 1 or 3 -> 3, specular 3).
AFN_IO_API int roleComponents(Role role);

/// Conventions of a role's values, named exactly as the filter parameters of libafn
/// ("normal.space", "depth.kind", "motion.direction", "motion.yUp", "motion.units").
struct SpaceTag {
    std::string normalSpace = "world"; ///< world | camera | camera-toward-viewer
    std::string depthKind = "planar"; ///< planar | radial
    std::string motionDirection = "to-previous"; ///< to-previous | to-next
    bool motionYUp = false; ///< y grows upward (Blender)
    std::string motionUnits = "pixels"; ///< pixels | ndc | uv
    bool colorDemodulated = false; ///< colour already divided by albedo (BMFR data)

    /// The conventions as (filter parameter name, value) pairs, to be set on a filter in a loop.
    AFN_IO_API std::vector<std::pair<std::string, std::string>> parameters() const;
};

/// Where one role lives in a file.
struct RoleChannels {
    Role role = Role::Color;
    int subimage = 0; ///< part (subimage) index
    std::vector<std::string> channels; ///< full channel names, in component order (R,G,B / X,Y,Z)
    std::vector<int> indices; ///< channel indices within the subimage
    std::string source; ///< e.g. "Blender Cycles 'Denoising Albedo'" or "--aov override"
};

/// The role mapping of one file.
struct RoleMapping {
    std::string renderer
        = "generic"; ///< blender | arnold | renderman | vray | redshift | karma | bmfr | generic
    std::vector<RoleChannels> roles; ///< roles found, in Role order
    SpaceTag tag; ///< conventions of normal, depth and motion as found
    /// For every role not found: the names actually tried, as --aov would spell them (layers such
    /// as "albedo" or "ViewLayer.DiffCol", top-level channels such as "R,G,B"): the chosen
    /// preset's, then the generic ones (a colour found nowhere: every preset's).
    std::map<Role, std::vector<std::string>> lookedFor;
    /// Labels of the naming conventions applied, in order: the chosen preset ("Blender Cycles"),
    /// then "generic" for roles the preset left unmapped.
    std::vector<std::string> presetsTried;
    /// Things the user should know (e.g. "Vector pass is all zero: motion blur was on").
    std::vector<std::string> warnings;

    AFN_IO_API const RoleChannels* find(Role role) const;
};

/// A user override: role -> comma-separated channel names, e.g.
/// "albedo=diffuse.R,diffuse.G,diffuse.B" or a layer prefix "albedo=diffuse". Space-tag overrides
/// use the filter parameter names
/// ("normal.space=camera").
struct MappingOverrides {
    std::map<Role, std::vector<std::string>> channels;
    std::map<std::string, std::string> tags; ///< "normal.space" -> "camera", ...
    /// "--aov lights=A,B*F,...": the additive light passes (layer names; "B*F": B multiplied by
    /// the colour factor layer F) replacing the renderer's recipe; an empty list ("lights=none")
    /// turns the light passes off. Unset: the renderer's recipe (findLightPasses).
    std::optional<std::vector<std::string>> lights;
};

/// Parse one "--aov" argument ("role=channels", "normal.space=value" or "lights=A,B*F"); throws
/// IoError.
AFN_IO_API void parseOverride(const std::string& text, MappingOverrides& overrides);

// ---- File inspection ----------------------------------------------------------------------------

struct Box {
    int x = 0, y = 0, width = 0, height = 0;
};

struct SubimageInfo {
    std::string name; ///< part name ("" for single-part files)
    Box dataWindow;
    Box displayWindow;
    std::vector<std::string> channels; ///< names as stored
    std::vector<std::string> types; ///< per channel: "half", "float", "uint"
    std::string compression;
};

struct FileInfo {
    std::string path;
    std::string format; ///< "openexr", "png", ...
    std::vector<SubimageInfo> subimages;
    std::map<std::string, std::string> attributes; ///< header attributes of subimage 0, as text
};

/// Read a file's header; throws IoError (missing, unreadable, truncated header).
AFN_IO_API FileInfo inspect(const std::string& path);

/// Samples per pixel the renderer recorded in the header: Blender Cycles'
/// `cycles.<view layer>.samples`, the layer that `colorChannel` (e.g. "ViewLayer.Combined.R")
/// belongs to, or the only such attribute. nullopt when absent, ambiguous or not a positive
/// integer.
AFN_IO_API std::optional<int> samplesPerPixel(
    const FileInfo& info, const std::string& colorChannel = {});

/// Map channels to roles (automatic for Blender Cycles, Arnold, RenderMan, V-Ray, Redshift, Karma,
/// generic R,G,B), then apply overrides. A preset is chosen by the header (e.g. Blender's
/// attributes) or by the names it explains; roles it leaves unmapped fall back to the generic
/// names ("albedo", "N", "P", "Z", "motionvector", ...). Never throws for a missing role (see
/// lookedFor); throws IoError when an override names channels the file does not have. An override
/// "ROLE=none" unbinds the role (as if the file lacked it; not allowed for colour).
AFN_IO_API RoleMapping mapRoles(const FileInfo& info, const MappingOverrides& overrides = {});

// ---- Light-path passes --------------------------------------------------------------------------

/// One light-path pass of a file: an additive light pass, or a colour factor (albedo-like, e.g.
/// Blender's DiffCol) a light pass is multiplied by.
struct LightPass {
    std::string name; ///< as the renderer names it: "DiffDir", "diffuse_direct", "VRayLighting"
    int subimage = 0;
    std::vector<std::string> channels; ///< full channel names, in R,G,B order
    std::vector<int> indices; ///< channel indices within the subimage
    std::string factor; ///< light passes: the factor pass it is multiplied by ("DiffCol"); ""
};

/// How a file's beauty is rebuilt from its passes (lib/io/light_passes.cpp has the recipes):
/// beauty = sum over `lights` of light x (its factor, or 1).
struct PassRecipe {
    std::string renderer; ///< the preset whose names were found ("blender", ...; "--aov lights")
    std::vector<LightPass> lights; ///< additive passes, in the order of the renderer's formula
    std::vector<LightPass> factors; ///< colour factors (albedo-like: not denoised)
    std::string formula; ///< "Combined = (DiffDir + DiffInd) x DiffCol + ... + Env" as found
    /// Passes of a partly written family (DiffInd without DiffDir): the sum cannot match.
    std::vector<std::string> missing;
    bool empty() const { return lights.empty(); }
    AFN_IO_API const LightPass* find(const std::string& name) const;
};

/// The light-path passes of a file by its renderer's names (Blender Cycles, Arnold, V-Ray; light
/// groups when a file has no light passes), or by overrides.lights. Empty when it has none.
/// Throws IoError when an override names a layer the file lacks.
AFN_IO_API PassRecipe findLightPasses(
    const FileInfo& info, const RoleMapping& mapping, const MappingOverrides& overrides = {});

/// How far the recomposed passes are from the beauty.
struct Recomposition {
    double psnr = 0; ///< dB on T(x) = clip(max(x,0)^(1/2.2), 0, 1), as afn's metrics; +inf if equal
    double maxAbsolute = 0; ///< largest |sum - beauty| over the RGB values (linear)
    double meanBeauty = 0; ///< mean beauty value, for scale
    /// sqrt(mean((sum - beauty)^2)) / mean(|beauty|) on linear values: sees what the tone map's
    /// clip at 1 hides (bright pixels).
    double relativeRms = 0;
};
/// PSNR (tone-mapped, as afn's metrics) under which recomposed passes count as not adding up to
/// the beauty (half-float passes of a matching file reach 60 dB and more).
constexpr double kRecompositionWarnPsnr = 40.0;
/// Linear relative RMS error above which they do not add up either (half floats: about 1e-3).
constexpr double kRecompositionWarnRelative = 0.01;

// ---- Reading frames -----------------------------------------------------------------------------

/// A role's pixels: interleaved floats, `components` per pixel, top row first, data window size.
struct RoleImage {
    int width = 0, height = 0, components = 0;
    std::vector<float> pixels;
};

/// Per-role statistics over all components (for --info).
struct RoleStats {
    double min = 0, max = 0, mean = 0;
    long long nan = 0, inf = 0, negative = 0, count = 0;
};
AFN_IO_API RoleStats computeStats(const RoleImage& image);

/// Every channel of a file (all subimages of the data window size), for --keep-aovs.
struct LayeredImage {
    int width = 0, height = 0;
    Box dataWindow, displayWindow;
    std::vector<std::string> channels; ///< names; parts of multi-part files as "<part>.<name>"
    std::vector<std::string> types; ///< per channel: "half" | "float" | "uint"
    std::vector<float> pixels; ///< interleaved, channels.size() per pixel
    std::map<std::string, std::string> attributes; ///< header attributes worth keeping (Frame, ...)
    std::string compression;
};

/// Camera of a frame, when the input provides one (BMFR camera_matrices.h).
struct FrameCamera {
    float viewProjection[16]; ///< row-major, clip = [p, 1]·M
    float pixelOffset[2];
    float positionLimitSquared; ///< dataset's TA thresholds (< 0 when unknown)
    float normalLimitSquared;
};

/// A header attribute, kept with its type so that outputs carry it over unchanged.
struct Attribute {
    std::string name;
    std::string
        type; ///< OpenImageIO type name: "string", "int", "float", "matrix", "float[8]", ...
    std::string text; ///< the value of a "string" attribute
    std::vector<unsigned char> data; ///< the raw value of any other type (native byte order)
};

/// What an output needs to be faithful to its input: windows, types, header metadata.
struct FrameHeader {
    std::string format; ///< "openexr", "png", "tiff", ... ("" for the BMFR layout)
    Box dataWindow; ///< of the part the colour was read from (the pixels of every role)
    Box displayWindow; ///< (the "format" of Nuke, full window of OpenImageIO)
    std::string colorType; ///< stored type of the colour channels: uint8 | uint16 | half | float...
    std::string compression; ///< "" when the format has none
    std::string colorSpace; ///< oiio:ColorSpace as OpenImageIO reports it ("" = none)
    std::string colorInteropId; ///< the colorInteropID attribute ("" = none)
    /// Every attribute worth carrying to an output (Camera, worldToCamera, Frame, RenderTime,
    /// cycles.*, PixelAspectRatio, ...), in file order. File structure (compression, part names,
    /// tiles, chunkCount), format-specific (oiio:, openexr:, png:, tiff:, ...), DateTime
    /// (restamped), Software and the colour-space tags (oiio:ColorSpace, colorInteropID,
    /// chromaticities: the writer sets them for the output) are left out; so are types OpenImageIO
    /// cannot name back.
    std::vector<Attribute> attributes;
};

struct FrameImages {
    std::string path;
    FrameHeader header;
    RoleMapping mapping;
    std::map<Role, RoleImage> roles; ///< every mapped role
    std::optional<LayeredImage> all; ///< filled when ReadOptions::keepAll
    std::optional<FrameCamera> camera;
    std::optional<int> samples; ///< samples per pixel from the header (samplesPerPixel)
    /// Ground truth when the input provides one (BMFR reference{N}.exr, full radiance), else empty.
    std::optional<RoleImage> reference;
    PassRecipe passRecipe; ///< the file's light-path passes (findLightPasses); always filled
    /// Pixels of every pass of passRecipe (lights and factors, 3 components), by name, when
    /// ReadOptions::passes.
    std::map<std::string, RoleImage> passes;
};

/// The beauty rebuilt from `passes` by `recipe` (width x height x 3); passes it lacks count as 0.
AFN_IO_API RoleImage recompose(const PassRecipe& recipe,
    const std::map<std::string, RoleImage>& passes, int width, int height);
/// Error of a recomposition against a beauty (first 3 components of each).
AFN_IO_API Recomposition recompositionError(const RoleImage& recomposed, const RoleImage& beauty);
/// The recomposition of a read frame (readFrame with ReadOptions::passes) against its colour;
/// nullopt when it has no light passes or no colour.
AFN_IO_API std::optional<Recomposition> recompositionOf(const FrameImages& frame);
/// A warning naming the error when the passes do not add up to the beauty (PSNR below
/// kRecompositionWarnPsnr, relative RMS above kRecompositionWarnRelative, or a family written only
/// in part); "" when they do.
AFN_IO_API std::string recompositionWarning(const PassRecipe& recipe, const Recomposition& error);

struct ReadOptions {
    MappingOverrides overrides;
    bool keepAll = false; ///< also read every channel (for --keep-aovs)
    bool passes = false; ///< also read the pixels of the light-path passes (FrameImages::passes)
    std::vector<Role> required = { Role::Color }; ///< missing -> IoError naming what was looked for
};

/// Read one frame (single EXR, multi-part EXR, or a BMFR dataset frame: see bmfrFramePath).
AFN_IO_API FrameImages readFrame(const std::string& path, const ReadOptions& options = {});

// ---- Sequences ----------------------------------------------------------------------------------

/// Parse oiiotool-style frame ranges: "1-10", "1-10x2", "3,5,7", "1-4,10". Throws IoError.
AFN_IO_API std::vector<int> parseFrameRange(const std::string& text);
/// True when the name holds a frame pattern: '#' (4 digits each), '@' (1 digit each), %0Nd.
/// A lone '#' is 4 digits (oiiotool); a run of '#' is one digit each ("####" = 4, as in Nuke).
AFN_IO_API bool hasFramePattern(const std::string& pattern);
/// Substitute a frame number ("shot.####.exr", 7 -> "shot.0007.exr"; negative frames keep '-').
AFN_IO_API std::string expandFramePattern(const std::string& pattern, int frame);
/// Expand for every frame and check each file exists; throws IoError naming the first missing.
AFN_IO_API std::vector<std::string> expandSequence(
    const std::string& pattern, const std::vector<int>& frames, bool mustExist = true);

// ---- BMFR dataset layout ------------------------------------------------------------------------

/// True if `dir` (or dir/inputs) holds color{N}.exr + camera_matrices.h.
AFN_IO_API bool isBmfrDataset(const std::string& dir);
/// The per-frame pseudo path for frame N of a BMFR scene folder ("<dir>#bmfr:N"), readable by
/// readFrame.
AFN_IO_API std::string bmfrFramePath(const std::string& dir, int frame);
/// Parse camera_matrices.h (named arrays, not a number regex): all frames.
AFN_IO_API std::vector<FrameCamera> parseCameraMatrices(const std::string& headerPath);

// ---- Writing ------------------------------------------------------------------------------------

/// What a file format (chosen by the output's extension) can store.
struct OutputFormat {
    std::string name; ///< OpenImageIO format name: "openexr", "png", "tiff", "jpeg", ...
    std::vector<std::string> dataTypes; ///< storable types, e.g. {"half", "float", "uint"}
    std::vector<std::string> compressions; ///< accepted --compression names ("" = none accepted)
    bool windows = false; ///< stores data and display windows (else cropped/padded to display)

    /// The type to store when `wanted` is not storable: integers in a float-only format become
    /// half (uint8) or float (wider), floats in an integer-only format uint8 (as OpenImageIO).
    AFN_IO_API std::string storedType(const std::string& wanted) const;
    /// True when `compression` (its name before any ':level') is in `compressions`.
    AFN_IO_API bool acceptsCompression(const std::string& compression) const;
};

/// The format an output path would be written in (by its extension); throws IoError when no
/// writer exists for it.
AFN_IO_API OutputFormat outputFormat(const std::string& path);

struct WriteOptions {
    /// "uint8" | "uint16" | "half" | "float" (and "uint" per channel in EXR); must be storable in
    /// the format (OutputFormat::dataTypes), else IoError. "" = the format's usual: uint8 where
    /// the format stores it (PNG, TIFF, JPEG), else half (EXR), else float (HDR, PFM).
    std::string dataType;
    std::string compression; ///< "" = the format's default (zip for EXR); else validated
    std::map<std::string, std::string> attributes; ///< extra string attributes (win over metadata)
    std::vector<Attribute> metadata; ///< typed attributes carried from an input (FrameHeader)
    /// Where the pixels lie (size must equal the image's) and the display window; empty = at
    /// (0, 0) with display window = data window. Formats without windows get the display window:
    /// pixels outside the data window are 0, data outside the display window is cropped
    /// (oiiotool's autocrop, Nuke's Write).
    std::optional<Box> dataWindow, displayWindow;
    std::vector<std::string> inputs; ///< paths that must never be overwritten (refuse if equal)
};

/// Write an image atomically: temporary file in the same directory, then rename. The format comes
/// from the extension (.exr, .png, .tif, ...). `types` may give a per-channel type (empty =
/// options.dataType). In half channels, finite values beyond the half range are clamped to
/// +-65504 (they would otherwise become +-Inf); NaN and Inf are written as they are. Integer
/// channels hold [0, 1] (values clamped, NaN -> 0).
/// Throws IoError; on failure nothing is left at `path` or beside it.
AFN_IO_API void writeImageAtomic(const std::string& path, int width, int height,
    const std::vector<std::string>& channels, const float* pixels, const WriteOptions& options = {},
    const std::vector<std::string>& types = {});

/// True if two paths name the same existing file (or the same path when they do not exist yet).
AFN_IO_API bool samePath(const std::string& a, const std::string& b);

} // namespace afn::io
