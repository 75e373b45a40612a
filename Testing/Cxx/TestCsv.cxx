// catar::CsvField: plain fields unchanged, fields with separators quoted, quotes doubled.
#include "Csv.h"

#include <gtest/gtest.h>

TEST(Csv, FieldsAreQuotedOnlyWhenNeeded)
{
  EXPECT_EQ(catar::CsvField(""), "");
  EXPECT_EQ(catar::CsvField("bunny"), "bunny");
  EXPECT_EQ(catar::CsvField("1 spot; gouraud"), "1 spot; gouraud");
  EXPECT_EQ(catar::CsvField("1 spot, gouraud"), "\"1 spot, gouraud\"");
  EXPECT_EQ(catar::CsvField("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(catar::CsvField("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(catar::CsvField("\""), "\"\"\"\"");
}
