// A volume sampled from a function of the grid point, for tests of every module.
#pragma once

#include "vots/fit/Volume.h"

#include <array>
#include <functional>

namespace vots::test {

/// f(x, y, z) at every grid point (index coordinates), as float.
inline fit::Volume sampleVolume(const std::array<int, 3>& dims, const std::function<double(int, int, int)>& f,
                                const std::array<double, 3>& spacing = {1.0, 1.0, 1.0}) {
    fit::Volume v;
    v.dims = dims;
    v.spacing = spacing;
    v.name = "synthetic";
    v.values.resize(v.sampleCount());
    for (int z = 0; z < dims[2]; ++z)
        for (int y = 0; y < dims[1]; ++y)
            for (int x = 0; x < dims[0]; ++x)
                v.values[v.indexOf(x, y, z)] = static_cast<float>(f(x, y, z));
    return v;
}

} // namespace vots::test
