#include "io/locate.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace iga::io {

TEST(Locate, FindsItemsByNameAndIndexAndStopsAtTheDeepestExistingNode)
{
    const auto path = std::filesystem::temp_directory_path() / "igacontact_locate_test.yaml";
    std::ofstream(path) << "format: 1\n"
                           "materials:\n"
                           "  - {name: steel, E: 1.0, nu: 0.3}\n"
                           "loads:\n"
                           "  - {body: b, side: v1, force: [0, 1]}\n"
                           "  - {body: b, side: v0, force: [0, 2]}\n";
    const std::string file = path.string();
    EXPECT_EQ(locate(file, "materials.steel.nu").line, 3);
    EXPECT_EQ(locate(file, "materials.steel.nu").column, 31);
    EXPECT_EQ(locate(file, "loads.1").line, 6);
    EXPECT_EQ(locate(file, "loads.1").column, 5);
    EXPECT_EQ(locate(file, "loads.7").line, 5);   // no item 7: the list itself (its first item)
    EXPECT_EQ(locate(file, "nothing.here").line, 0);  // nothing of the path exists: the file alone
    EXPECT_EQ(located_issue(file, "loads.1", "", "bad").format(), file + ":6:5: error: loads.1: bad");
    EXPECT_EQ(locate("/nonexistent/deck.yaml", "loads").line, 0);
    std::filesystem::remove(path);
}

}  // namespace iga::io
