// Reads headerless raw volumes whose layout (dims, type, byte order, header skip) the caller supplies.
#include "vots/fit/VolumeLoad.h"

#include "HeaderText.h"
#include "InputFile.h"
#include "SampleDecode.h"
#include "StoredSamples.h"

namespace vots::fit {

using namespace detail;

StoredSamples detail::storedRawSamples(const std::string& path, const RawLayout& layout) {
    const std::uint64_t fileSize = regularFileSize(path);
    const CheckedShape shape =
        checkShape(path, {layout.dims[0], layout.dims[1], layout.dims[2]}, layout.type);
    Volume volume;
    volume.dims = shape.dims;
    for (int a = 0; a < 3; ++a)
        volume.spacing[a] = checkedSpacing(path, "raw spacing", layout.spacing[a]);
    volume.sourceType = layout.type;
    volume.name = fileStem(path);

    // The layout must account for every byte: a mismatch almost always means wrong dims or type.
    const std::uint64_t expected = static_cast<std::uint64_t>(layout.headerBytes) + shape.bytes;
    if (fileSize != expected)
        throwInputError(path, "has " + std::to_string(fileSize) + " bytes but the raw layout " +
                                  std::to_string(shape.dims[0]) + "x" + std::to_string(shape.dims[1]) + "x" +
                                  std::to_string(shape.dims[2]) + " " + scalarTypeName(layout.type) +
                                  " with " + std::to_string(layout.headerBytes) + " header bytes needs " +
                                  std::to_string(expected));
    return {{std::move(volume), layout.type, layout.bigEndian, 0.0, 0.0},
            {{path, layout.headerBytes, shape.bytes}}};
}

Volume loadRaw(const std::string& path, const RawLayout& layout, SampleStorage storage) {
    return readStoredVolume(path, storedRawSamples(path, layout), storage);
}

} // namespace vots::fit
