// Private to the DICOM reader: one slice's pixels, decoded by GDCM in the child and rescaled in the parent.
#pragma once

#include "DicomChild.h"
#include "DicomScan.h"
#include "InputFile.h"

#include "vots/fit/Volume.h"
#include "vots/fit/VolumeLoad.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

namespace vots::fit::detail {

/// How the child's decoded pixels are laid out, sent before each slice's bytes.
struct SliceFormat {
    int bitsAllocated = 16;
    int bitsStored = 16;
    int highBit = 15;
    int pixelsSigned = 0;
};

/// One stored pixel as an integer: masked to BitsStored and sign-extended when the pixels are signed, so
/// bits above HighBit (overlays, garbage) never change a value.
struct PixelDecoder {
    int bytes = 2;
    int shift = 0;
    std::uint32_t mask = 0xffff;
    std::uint32_t signBit = 0;

    explicit PixelDecoder(const SliceFormat& format) {
        bytes = format.bitsAllocated / 8;
        const int stored = std::clamp(format.bitsStored, 1, format.bitsAllocated);
        shift = std::clamp(format.highBit + 1 - stored, 0, format.bitsAllocated - stored);
        mask = stored >= 32 ? 0xffffffffu : (1u << stored) - 1u;
        signBit = format.pixelsSigned != 0 ? 1u << (stored - 1) : 0u;
    }
    long long at(const char* buffer, std::size_t index) const {
        std::uint32_t raw = 0;
        if (bytes == 1) raw = static_cast<unsigned char>(buffer[index]);
        if (bytes == 2) {
            std::uint16_t v;
            std::memcpy(&v, buffer + 2 * index, 2);
            raw = v;
        }
        if (bytes == 4) std::memcpy(&raw, buffer + 4 * index, 4);
        raw = (raw >> shift) & mask;
        if (signBit != 0 && (raw & signBit) != 0)
            return static_cast<long long>(raw) - 2 * static_cast<long long>(signBit);
        return static_cast<long long>(raw);
    }
};

/// In the child: the last file decodeAndSend decoded, kept so that the frames of a multi-frame instance,
/// sent one by one, decode their file once.
struct DecodedFile {
    std::string path;
    SliceFormat format;
    std::vector<char> pixels; // every frame's
};

/// In the child: decodes the slice (frame slice.frameIndex of its file) with GDCM and sends its format,
/// then exactly its pixel bytes. Throws InputError when its image is not `dims` (columns, rows) by
/// slice.frames frames or cannot be decoded.
void decodeAndSend(const DicomSliceHeader& slice, const std::array<int, 3>& dims, ChildSender& child,
                   DecodedFile& last);

/// In the parent: receives what decodeAndSend sent for `header`'s file and stores its `pixels` values,
/// rescaled, at `out`; `buffer` is scratch kept between slices.
template <typename T>
void receiveSlice(const DicomSliceHeader& header, std::size_t pixels, ParentReceiver& parent,
                  std::vector<char>& buffer, T* out) {
    SliceFormat format;
    parent.nextInto(reinterpret_cast<char*>(&format), sizeof format);
    buffer.resize(pixels * static_cast<std::size_t>(format.bitsAllocated / 8));
    parent.nextInto(buffer.data(), buffer.size());
    const PixelDecoder decoder(format);
    for (std::size_t i = 0; i < pixels; ++i) {
        const double value =
            header.slope * static_cast<double>(decoder.at(buffer.data(), i)) + header.intercept;
        if constexpr (std::is_integral_v<T>) {
            // The type was chosen from BitsStored; pixel data beyond it contradicts the header.
            if (value < static_cast<double>(std::numeric_limits<T>::lowest()) ||
                value > static_cast<double>(std::numeric_limits<T>::max()))
                throwInputError(header.path, "a pixel value is outside the range its BitsStored announces");
        }
        out[i] = static_cast<T>(value);
    }
}

/// Calls `store(samples)` with the vector a series of `type` is held in under `storage`: the source's 8-
/// or 16-bit type in `compact` for SampleStorage::Source, floats in `values` otherwise (emplaced empty).
template <typename Store>
void withStoredSamples(Volume& into, ScalarType type, SampleStorage storage, Store&& store) {
    const bool compact = storage == SampleStorage::Source && type != ScalarType::Float32;
    if (!compact) {
        store(into.values);
    } else if (type == ScalarType::UInt8) {
        store(into.compact.emplace<std::vector<std::uint8_t>>());
    } else if (type == ScalarType::Int16) {
        store(into.compact.emplace<std::vector<std::int16_t>>());
    } else {
        store(into.compact.emplace<std::vector<std::uint16_t>>());
    }
}

} // namespace vots::fit::detail
