// The functional groups of multi-frame instances (Enhanced CT/MR, ...) read into a slice header.
#include "DicomFunctionalGroups.h"

#include "DicomText.h"

#include <gdcmSequenceOfItems.h>

#include <algorithm>
#include <utility>

namespace vots::fit::detail {
namespace {

// The functional groups and the macros read from them.
const gdcm::Tag SHARED_GROUPS(0x5200, 0x9229), PER_FRAME_GROUPS(0x5200, 0x9230);
const gdcm::Tag PLANE_POSITION(0x0020, 0x9113), PLANE_ORIENTATION(0x0020, 0x9116);
const gdcm::Tag PIXEL_MEASURES(0x0028, 0x9110), FRAME_CONTENT(0x0020, 0x9111),
    VALUE_TRANSFORM(0x0028, 0x9145);

/// The items of sequence `tag` in `data`; null when it is absent or not a sequence.
gdcm::SmartPointer<gdcm::SequenceOfItems> itemsOf(const gdcm::DataSet& data, const gdcm::Tag& tag) {
    if (!data.FindDataElement(tag) || data.GetDataElement(tag).IsEmpty()) return nullptr;
    return data.GetDataElement(tag).GetValueAsSQ();
}

/// The value of (group, element) in the first item of macro sequence `macro` of a functional group's data
/// set (`groups`, null for none); "" when absent.
std::string macroText(const gdcm::StringFilter& filter, const gdcm::DataSet* groups, const gdcm::Tag& macro,
                      std::uint16_t group, std::uint16_t element) {
    if (groups == nullptr) return {};
    const gdcm::SmartPointer<gdcm::SequenceOfItems> items = itemsOf(*groups, macro);
    if (!items || items->GetNumberOfItems() == 0) return {};
    return textOf(filter, items->GetItem(1).GetNestedDataSet(), group, element);
}

} // namespace

void readFunctionalGroups(const gdcm::StringFilter& filter, const gdcm::DataSet& data,
                          DicomSliceHeader& slice) {
    const gdcm::SmartPointer<gdcm::SequenceOfItems> sharedItems = itemsOf(data, SHARED_GROUPS);
    const gdcm::DataSet* shared = sharedItems && sharedItems->GetNumberOfItems() > 0
                                      ? &sharedItems->GetItem(1).GetNestedDataSet()
                                      : nullptr;
    const gdcm::SmartPointer<gdcm::SequenceOfItems> perFrame = itemsOf(data, PER_FRAME_GROUPS);
    const gdcm::DataSet* firstFrame =
        perFrame && perFrame->GetNumberOfItems() > 0 ? &perFrame->GetItem(1).GetNestedDataSet() : nullptr;
    const auto sharedOrFirst = [&](const gdcm::Tag& macro, std::uint16_t group, std::uint16_t element) {
        const std::string text = macroText(filter, shared, macro, group, element);
        return text.empty() ? macroText(filter, firstFrame, macro, group, element) : text;
    };
    if (!numbersOf(textOf(filter, data, 0x0020, 0x0037), 6))
        if (const auto orientation = numbersOf(sharedOrFirst(PLANE_ORIENTATION, 0x0020, 0x0037), 6))
            std::copy(orientation->begin(), orientation->end(), slice.orientation.begin());
    if (!numbersOf(textOf(filter, data, 0x0028, 0x0030), 2))
        if (const auto spacing = numbersOf(sharedOrFirst(PIXEL_MEASURES, 0x0028, 0x0030), 2))
            slice.pixelSpacing = {(*spacing)[0], (*spacing)[1]};
    if (!numbersOf(textOf(filter, data, 0x0028, 0x1053), 1)) {
        if (const auto slope = numbersOf(sharedOrFirst(VALUE_TRANSFORM, 0x0028, 0x1053), 1))
            slice.slope = (*slope)[0];
        if (const auto intercept = numbersOf(sharedOrFirst(VALUE_TRANSFORM, 0x0028, 0x1052), 1))
            slice.intercept = (*intercept)[0];
    }
    for (const auto& [group, element] : {std::pair{0x0018, 0x0088}, std::pair{0x0018, 0x0050}}) {
        std::string text = textOf(filter, data, group, element);
        if (text.empty()) text = sharedOrFirst(PIXEL_MEASURES, group, element);
        if (const auto gap = numbersOf(text, 1); gap && (*gap)[0] > 0) {
            slice.frameGap = (*gap)[0];
            break;
        }
    }
    if (!perFrame) return;
    bool placed = false;
    for (gdcm::SequenceOfItems::SizeType i = 1; i <= perFrame->GetNumberOfItems(); ++i) {
        const gdcm::DataSet* frame = &perFrame->GetItem(i).GetNestedDataSet();
        FramePlace place;
        place.slope = slice.slope;
        place.intercept = slice.intercept;
        if (const auto position = numbersOf(macroText(filter, frame, PLANE_POSITION, 0x0020, 0x0032), 3)) {
            place.hasPosition = 1;
            std::copy(position->begin(), position->end(), place.position);
            placed = true;
        }
        if (const auto time = numbersOf(macroText(filter, frame, FRAME_CONTENT, 0x0020, 0x9128), 1)) {
            place.hasTime = 1;
            place.timeOrder = (*time)[0];
        }
        if (const auto slope = numbersOf(macroText(filter, frame, VALUE_TRANSFORM, 0x0028, 0x1053), 1))
            place.slope = (*slope)[0];
        if (const auto intercept = numbersOf(macroText(filter, frame, VALUE_TRANSFORM, 0x0028, 0x1052), 1))
            place.intercept = (*intercept)[0];
        slice.framePlaces.push_back(place);
    }
    // Groups that place no frame (only a rescale, say) leave the frames a stack.
    if (!placed) slice.framePlaces.clear();
}
} // namespace vots::fit::detail
