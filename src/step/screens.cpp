#include "step/screens.h"

#include <sstream>

namespace facet::step {

std::string printWalk(const Walk& walk) {
    std::ostringstream out;
    out << "Pixel (" << walk.x << ", " << walk.y << "): " << walk.verdict << "\n";
    for (std::size_t k = 0; k < walk.screens.size(); ++k) {
        const Screen& screen = walk.screens[k];
        out << "\n"
            << std::string(80, '=') << "\n"
            << k + 1 << ". " << screen.title << "\n"
            << std::string(80, '=') << "\n"
            << screen.text;
    }
    return out.str();
}

}  // namespace facet::step
