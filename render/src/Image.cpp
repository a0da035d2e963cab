// Image size validation shared by every renderer and the PNG encoder.
#include "vots/render/Image.h"

#include "vots/fit/Error.h"

#include <string>

namespace vots::render {

void checkImageSize(int width, int height) {
    if (width < 1 || height < 1 || width > MAX_IMAGE_SIDE || height > MAX_IMAGE_SIDE)
        throw fit::InputError("image size " + std::to_string(width) + "x" + std::to_string(height) +
                              " outside 1.." + std::to_string(MAX_IMAGE_SIDE));
}

} // namespace vots::render
