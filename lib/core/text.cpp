#include "core/text.hpp"

#include <cstdio>

namespace iga {

std::string point_text(const VecN& x, int significant)
{
    std::string out = "(";
    char buffer[64];
    for (Index i = 0; i < x.size(); ++i) {
        std::snprintf(buffer, sizeof buffer, "%.*g", significant, x(i));
        out += (i > 0 ? ", " : "") + std::string(buffer);
    }
    return out + ")";
}

std::string point_text(const RowMatrix& points, Index row, int significant)
{
    return point_text(VecN(points.row(row).transpose()), significant);
}

}  // namespace iga
