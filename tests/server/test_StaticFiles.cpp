// StaticFiles: hostile targets are recognised; resolution never leaves the web folder.
#include "routes/StaticFiles.h"

#include "TempDir.h"

#include <gtest/gtest.h>

namespace vots::server {
namespace {

TEST(StaticFiles, RecognisesHostileTargets) {
    for (const char* t : {"/../x", "/%2e%2e/x", "/%2E%2e/x", "/.%2e/x", "/a\\b", "/a%5cb", "/a%00b", "/?d=..",
                          "/%252e%252e/"})
        EXPECT_TRUE(isHostileTarget(t)) << t;
    for (const char* t : {"/", "/index.html", "/render?dataset=a&eps=2%25", "/js/app.js", "/a.b/c"})
        EXPECT_FALSE(isHostileTarget(t)) << t;
}

TEST(StaticFiles, ResolvesOnlyServedFilesInsideTheRoot) {
    test::TempDir dir;
    std::filesystem::create_directories(dir.path() / "web" / "js");
    dir.write("web/index.html", "x");
    dir.write("web/js/app.js", "x");
    dir.write("web/notes.txt", "x");
    dir.write("outside.html", "x");
    std::filesystem::create_symlink(dir.path() / "outside.html", dir.path() / "web" / "out.html");
    const auto web = dir.path() / "web";
    EXPECT_TRUE(resolveStaticFile(web, "/"));
    EXPECT_TRUE(resolveStaticFile(web, "/js/app.js"));
    EXPECT_FALSE(resolveStaticFile(web, "/notes.txt")); // not a served type
    EXPECT_FALSE(resolveStaticFile(web, "/out.html"));  // symlink out of the root
    EXPECT_FALSE(resolveStaticFile(web, "/../outside.html"));
    EXPECT_FALSE(resolveStaticFile(web, "/js")); // a folder
    EXPECT_FALSE(resolveStaticFile({}, "/"));
    EXPECT_EQ(contentTypeFor("a.svg"), "image/svg+xml");
    EXPECT_EQ(contentTypeFor("a.PNG"), "image/png");
    EXPECT_EQ(contentTypeFor("a.exe"), "");
}

} // namespace
} // namespace vots::server
