// The status line drawn on a terminal: what fits, in which order (the drawing itself is
// checked on a pseudo-terminal in test_cli).
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "progress.hpp"

using packbed::cli::fit_status_line;

TEST(Progress, StatusLineFitsByDroppingTheLeastImportantFields) {
    const std::vector<std::string> f{"12.0 s", "intermediate", "overlaps 6.1e-03/2.0e-03 Dp",
                                     "it 123456"};
    // 6 + 2 + 12 + 2 + 27 + 2 + 9 = 60 characters
    EXPECT_EQ(fit_status_line(f, 61).size(), 60u);
    EXPECT_EQ(fit_status_line(f, 60), "12.0 s  intermediate  overlaps 6.1e-03/2.0e-03 Dp");
    EXPECT_EQ(fit_status_line(f, 32), "12.0 s  intermediate  it 123456"); // fills with the last
    EXPECT_EQ(fit_status_line(f, 5), "12.0"); // cut, never wider than the terminal
}
