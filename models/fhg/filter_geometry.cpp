#include "filter_geometry.h"

#include <stdexcept>
#include <string>

namespace surfvp::fhg {

std::vector<Box> filter_boxes(int size, Response response) {
    if (size < 9 || size % 6 != 3)
        throw std::invalid_argument("filter size must be 9, 15, 21, ...: " + std::to_string(size));
    const int l = size / 3, b = (size - 1) / 2, h = (l - 1) / 2;
    switch (response) {
        case Response::xx:
            return {{-b, -(l - 1), b, l - 1, 1}, {-h, -(l - 1), h, l - 1, -3}};
        case Response::yy:
            return {{-(l - 1), -b, l - 1, b, 1}, {-(l - 1), -h, l - 1, h, -3}};
        case Response::xy:
            return {{1, -l, l, -1, 1}, {-l, 1, -1, l, 1}, {-l, -l, -1, -1, -1}, {1, 1, l, l, -1}};
    }
    return {};
}

std::vector<Read> filter_reads(int size) {
    std::vector<Read> reads;
    for (Response r : {Response::xx, Response::yy, Response::xy})
        for (const Box& box : filter_boxes(size, r)) {
            // sum = I(x1, y1) - I(x0-1, y1) - I(x1, y0-1) + I(x0-1, y0-1)
            reads.push_back({box.x1, box.y1, box.weight, r});
            reads.push_back({box.x0 - 1, box.y1, -box.weight, r});
            reads.push_back({box.x1, box.y0 - 1, -box.weight, r});
            reads.push_back({box.x0 - 1, box.y0 - 1, box.weight, r});
        }
    return reads;
}

BlockDeterminant block_determinant(int k) {
    if (k < 0 || k >= kDeterminantsPerBlock) throw std::out_of_range("block determinant index " + std::to_string(k));
    if (k < 16) return {kSizes[k / 4], (k % 4) % 2, (k % 4) / 2};
    return {kSizes[4 + (k - 16)], 0, 0};
}

}  // namespace surfvp::fhg
