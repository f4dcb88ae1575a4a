// VTK AMR sets (see VtkAmrFile.h): the set's XML lists block files, each read as image data (VtkImageFile.h).
#include "io/vtk/VtkAmrFile.h"

#include "io/FileRead.h"
#include "io/vtk/VtkArrays.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>

namespace ripple::apps {

namespace {

using namespace vtk;

constexpr uint64_t kMaxSetFileBytes = uint64_t(1) << 26;  // the set's own XML: a list of block files
constexpr size_t kMaxBlocks = size_t(1) << 20;
// Relative tolerance of spacings that should agree, and how far a block's origin may be from its level's grid
// (in cells).
constexpr double kSpacingTolerance = 1e-4;
constexpr double kGridTolerance = 1e-3;

struct BlockFile {
    std::filesystem::path path;
    std::string named;                       // as the set names it
    int level = -1;                          // .vthb: the <Block level>
    std::optional<std::array<int, 6>> amrBox;  // .vthb: x0 x1 y0 y1 z0 z1, cells inclusive
};

struct SetListing {
    bool hierarchical = false;               // .vthb (levels and boxes given) rather than .vtm
    std::optional<glm::dvec3> origin;
    std::map<int, glm::dvec3> levelSpacing;  // .vthb: <Block spacing> per level
    std::vector<BlockFile> files;
};

std::optional<glm::dvec3> vectorAttribute(const std::filesystem::path& file, const pugi::xml_node& node, const char* name) {
    if (!node.attribute(name)) return std::nullopt;
    const std::vector<double> v = numbersIn(node.attribute(name).value());
    if (v.size() != 3 || !std::isfinite(v[0] + v[1] + v[2])) fail(file, std::string(name) + " '" + node.attribute(name).value() + "' is not three numbers");
    return glm::dvec3(v[0], v[1], v[2]);
}

void addFile(const std::filesystem::path& file, const pugi::xml_node& dataSet, SetListing& set, int level) {
    const std::string named = dataSet.attribute("file").value();
    if (named.empty()) return;  // an empty block
    if (set.files.size() >= kMaxBlocks) fail(file, "more than 2^20 blocks");
    std::string error;
    BlockFile block;
    block.named = named;
    block.path = resolveBeside(file, named, error);
    if (block.path.empty()) fail(file, "block file '" + named + "' " + error);
    block.level = level;
    if (set.hierarchical) {
        const std::vector<double> box = numbersIn(dataSet.attribute("amr_box").value());
        if (box.size() != 6) fail(file, "block file '" + named + "' has no amr_box of six integers");
        std::array<int, 6> b{};
        for (size_t i = 0; i < 6; ++i) {
            if (box[i] != std::floor(box[i]) || std::abs(box[i]) > double(1 << 24))
                fail(file, "block file '" + named + "' has an amr_box that is not six integers within +-2^24");
            b[i] = int(box[i]);
        }
        block.amrBox = b;
    }
    set.files.push_back(std::move(block));
}

// .vtm: DataSets anywhere under the multiblock element (Blocks nest).
void collectMultiblock(const std::filesystem::path& file, const pugi::xml_node& node, SetListing& set, int depth) {
    if (depth > 64) fail(file, "blocks nest more than 64 deep");
    for (const pugi::xml_node child : node.children()) {
        if (std::string(child.name()) == "DataSet") addFile(file, child, set, -1);
        else collectMultiblock(file, child, set, depth + 1);
    }
}

SetListing listSet(const std::filesystem::path& file) {
    const std::string text = readRegularFile(file, kMaxSetFileBytes, "");
    pugi::xml_document doc;
    if (!doc.load_buffer(text.data(), text.size())) fail(file, "is not XML");
    const pugi::xml_node root = doc.child("VTKFile");
    if (!root) fail(file, "has no <VTKFile> element");
    const std::string type = root.attribute("type").value();
    SetListing set;
    if (type == "vtkOverlappingAMR" || type == "vtkHierarchicalBoxDataSet") {
        set.hierarchical = true;
        const pugi::xml_node amr = root.child(type.c_str());
        if (!amr) fail(file, "has no <" + type + "> element");
        set.origin = vectorAttribute(file, amr, "origin");
        for (const pugi::xml_node level : amr.children("Block")) {
            const int index = level.attribute("level").as_int(-1);
            if (index < 0 || index > 30) fail(file, "a <Block> has no level from 0 to 30");
            if (const std::optional<glm::dvec3> spacing = vectorAttribute(file, level, "spacing")) set.levelSpacing[index] = *spacing;
            for (const pugi::xml_node dataSet : level.children("DataSet")) addFile(file, dataSet, set, index);
        }
    } else if (type == "vtkMultiBlockDataSet") {
        const pugi::xml_node multiblock = root.child(type.c_str());
        if (!multiblock) fail(file, "has no <" + type + "> element");
        collectMultiblock(file, multiblock, set, 0);
    } else {
        fail(file, "is a VTK '" + type + "' file; an AMR set is vtkOverlappingAMR, vtkHierarchicalBoxDataSet or vtkMultiBlockDataSet");
    }
    if (set.files.empty()) fail(file, "lists no block file");
    return set;
}

bool sameSpacing(const glm::dvec3& a, const glm::dvec3& b) {
    return glm::all(glm::lessThanEqual(glm::abs(a - b), kSpacingTolerance * glm::max(glm::abs(a), glm::abs(b))));
}

std::string vectorText(const glm::dvec3& v) {
    return std::to_string(v.x) + " " + std::to_string(v.y) + " " + std::to_string(v.z);
}

}  // namespace

bool isVtkAmrFile(const std::filesystem::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return extension == ".vthb" || extension == ".vth" || extension == ".vtm";
}

std::vector<VtkArrayInfo> listVtkAmrArrays(const std::filesystem::path& file) {
    return listVtkArrays(listSet(file).files.front().path);
}

AmrData readVtkAmr(const std::filesystem::path& file, const VtkFieldChoice& choice) {
    const SetListing set = listSet(file);
    std::vector<VtkImageCells> images;
    images.reserve(set.files.size());
    for (const BlockFile& b : set.files) {
        if (!isVtkImageFile(b.path) || b.path.extension() != ".vti")
            fail(file, "block file '" + b.named + "' is not a .vti file (image data); Ripple reads AMR blocks as image data");
        try {
            images.push_back(readVtkImageCells(b.path, choice));
        } catch (const VolumeError&) {
            throw;
        } catch (const std::runtime_error& e) {  // the file cannot be read at all (missing, not a regular file)
            fail(file, "block file '" + b.named + "': " + e.what());
        }
        if (images.size() > 1 && images.back().name != images.front().name)
            fail(b.path, "its array '" + images.back().name + "' is not the first block's '" + images.front().name + "'");
    }

    // Levels: .vthb gives them; .vtm's are its distinct spacings, coarsest first.
    std::vector<int> levelOf(images.size());
    std::map<int, glm::dvec3> spacing = set.levelSpacing;
    if (set.hierarchical) {
        for (size_t i = 0; i < images.size(); ++i) {
            levelOf[i] = set.files[i].level;
            const glm::dvec3 own(images[i].spacing);
            auto [at, added] = spacing.try_emplace(levelOf[i], own);
            if (!sameSpacing(at->second, own))
                fail(set.files[i].path, "its spacing " + vectorText(own) + " is not level " + std::to_string(levelOf[i]) + "'s (" +
                                            vectorText(at->second) + ")");
        }
    } else {
        std::vector<glm::dvec3> distinct;
        for (const VtkImageCells& image : images)
            if (std::none_of(distinct.begin(), distinct.end(), [&](const glm::dvec3& s) { return sameSpacing(s, glm::dvec3(image.spacing)); }))
                distinct.push_back(glm::dvec3(image.spacing));
        std::sort(distinct.begin(), distinct.end(), [](const glm::dvec3& a, const glm::dvec3& b) { return a.x > b.x; });
        for (size_t l = 0; l < distinct.size(); ++l) spacing[int(l)] = distinct[l];
        for (size_t i = 0; i < images.size(); ++i)
            for (size_t l = 0; l < distinct.size(); ++l)
                if (sameSpacing(distinct[l], glm::dvec3(images[i].spacing))) levelOf[i] = int(l);
    }
    const int levels = spacing.rbegin()->first + 1;
    AmrData out;
    const glm::dvec3 base = spacing.count(0) ? spacing.at(0) : glm::dvec3(0.0);
    if (!spacing.count(0)) fail(file, "level 0 has no spacing (no <Block spacing> and no block)");
    out.spacing = glm::vec3(base);
    for (int l = 0; l < levels; ++l) {
        if (!spacing.count(l)) fail(file, "level " + std::to_string(l) + " has no spacing (no <Block spacing> and no block)");
        const glm::dvec3 ratio = base / spacing.at(l);
        if (!(std::abs(ratio.y - ratio.x) <= kSpacingTolerance * ratio.x && std::abs(ratio.z - ratio.x) <= kSpacingTolerance * ratio.x))
            fail(file, "level " + std::to_string(l) + "'s spacing " + vectorText(spacing.at(l)) + " is not level 0's (" +
                           vectorText(base) + ") divided by one ratio on every axis");
        // Refinement ratios are whole numbers in VTK's AMR sets; the files round spacings to a few digits.
        const double whole = std::round(ratio.x);
        out.cellWidth.push_back(float(1.0 / (std::abs(ratio.x - whole) <= kSpacingTolerance * ratio.x ? whole : ratio.x)));
    }

    // The origin: the set's, else the lowest corner of the coarsest level's blocks.
    glm::dvec3 origin(INFINITY);
    if (set.origin) {
        origin = *set.origin;
    } else {
        const int coarsest = *std::min_element(levelOf.begin(), levelOf.end());
        for (size_t i = 0; i < images.size(); ++i)
            if (levelOf[i] == coarsest) origin = glm::min(origin, glm::dvec3(images[i].origin));
    }
    out.origin = glm::vec3(origin);

    out.blocks.resize(images.size());
    out.minValue = INFINITY;
    out.maxValue = -INFINITY;
    for (size_t i = 0; i < images.size(); ++i) {
        AmrData::Block& block = out.blocks[i];
        const VtkImageCells& image = images[i];
        block.level = uint32_t(levelOf[i]);
        // Where the block's origin sits on its level's grid (in its own cells: the set may round spacings).
        const glm::dvec3 at = (glm::dvec3(image.origin) - origin) / glm::dvec3(image.spacing);
        const glm::dvec3 nearest = glm::round(at);
        if (set.files[i].amrBox) {
            const std::array<int, 6>& box = *set.files[i].amrBox;
            block.lower = glm::ivec3(box[0], box[2], box[4]);
            block.upper = glm::ivec3(box[1], box[3], box[5]);
            const glm::ivec3 dims = block.upper - block.lower + 1;
            if (glm::any(glm::notEqual(glm::uvec3(glm::max(dims, 0)), image.cells)))
                fail(set.files[i].path, "its " + std::to_string(image.cells.x) + "x" + std::to_string(image.cells.y) + "x" +
                                            std::to_string(image.cells.z) + " cells disagree with the set's amr_box " +
                                            std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" + std::to_string(dims.z));
            if (glm::any(glm::greaterThan(glm::abs(at - glm::dvec3(block.lower)), glm::dvec3(kGridTolerance))))
                fail(set.files[i].path, "its origin is not where the set's amr_box puts it");
        } else {
            if (glm::any(glm::greaterThan(glm::abs(at - nearest), glm::dvec3(kGridTolerance))) ||
                glm::any(glm::greaterThan(glm::abs(nearest), glm::dvec3(double(1 << 24)))))
                fail(set.files[i].path, "its origin is not on level " + std::to_string(levelOf[i]) + "'s grid from " + vectorText(origin));
            block.lower = glm::ivec3(nearest);
            block.upper = block.lower + glm::ivec3(image.cells) - 1;
        }
        block.values = image.values;
        for (const float v : block.values) {
            out.minValue = std::min(out.minValue, v);
            out.maxValue = std::max(out.maxValue, v);
        }
        out.cells += block.values.size();
    }
    out.arrayName = images.front().name;
    return out;
}

}  // namespace ripple::apps
