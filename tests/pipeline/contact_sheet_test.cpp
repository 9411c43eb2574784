// Contact sheets: the grid, one painted member per cell, and the same bytes on any threads.
#include "pipeline/output/contact_sheet.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "test_util.h"

namespace pleinair {
namespace {

namespace fs = std::filesystem;

TEST(ContactSheet, GridGivesTheLargestPortraitCells) {
    int c, r;
    sheet_grid(12, 1920, 1080, c, r);
    EXPECT_EQ(c, 6);
    EXPECT_EQ(r, 2);
    sheet_grid(1, 1920, 1080, c, r);
    EXPECT_EQ(c * r, 1);
    sheet_grid(3, 300, 1000, c, r);  // a tall sheet stacks them
    EXPECT_EQ(c, 1);
    EXPECT_EQ(r, 3);
    sheet_grid(0, 100, 100, c, r);
    EXPECT_GE(c, 1);
    EXPECT_GE(r, 1);
}

TEST(ContactSheet, EveryCellHoldsAPaintedTreeAndThreadsDoNotMatter) {
    auto dir = test::temp_dir("sheet");
    auto a =
        test::run_pleinair("family --preset shrub --count 4 --seed 2 --width 320 --height 180 -o " +
                           (dir / "a.png").string());
    ASSERT_EQ(a.exit_code, 0) << a.err;
    auto b = test::run_pleinair(
        "family --preset shrub --count 4 --seed 2 --width 320 --height 180 "
        "--threads 1 -o " +
        (dir / "b.png").string());
    ASSERT_EQ(b.exit_code, 0) << b.err;
    EXPECT_EQ(test::read_file(dir / "a.png"), test::read_file(dir / "b.png"));

    auto in = OIIO::ImageInput::open((dir / "a.png").string());
    ASSERT_TRUE(in);
    ASSERT_EQ(in->spec().width, 320);
    ASSERT_EQ(in->spec().height, 180);
    std::vector<uint8_t> px(320 * 180 * 3);
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
    int cols, rows;
    sheet_grid(4, 320, 180, cols, rows);
    // Each cell has dark foliage pixels (a painted tree), not just sky and ground, counted
    // above the band of the seed's label (its dark digits alone would pass otherwise): the
    // cell's geometry as contact_sheet.cpp lays it out (6 pixels of gap, the label 9 rows
    // from the cell's foot at this size).
    const int gap = 6, cell_w = (320 - (cols + 1) * gap) / cols;
    const int cell_h = (180 - (rows + 1) * gap) / rows;
    for (int cell = 0; cell < 4; ++cell) {
        const int x0 = gap + (cell % cols) * (cell_w + gap),
                  y0 = gap + (cell / cols) * (cell_h + gap);
        int dark = 0;
        for (int y = y0; y < y0 + cell_h - 10; ++y)
            for (int x = x0; x < x0 + cell_w; ++x) {
                const uint8_t* p = &px[3 * (y * 320 + x)];
                dark += p[0] + p[1] + p[2] < 200 && p[1] >= p[2];
            }
        EXPECT_GT(dark, 100) << "cell " << cell;  // 215-606 when written
    }
    fs::remove_all(dir);
}

}  // namespace
}  // namespace pleinair
