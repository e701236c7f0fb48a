// studio/safe_path.h: a request path resolves only to a regular file inside its root.
#include "studio/safe_path.h"

#include <gtest/gtest.h>

#include "../temp_dir.h"
#include "studio/loopback.h"

namespace inet::studio {
namespace {

namespace fs = std::filesystem;

/// root/ with a file, a subfolder and a few symlinks; outside/ with a secret next to it.
class SafePathTest : public ::testing::Test {
 protected:
  void SetUp() override {
    tmp.write("root/index.html", "<p>in</p>");
    tmp.write("root/sub/a b.json", "{}");
    tmp.write("root/.hidden", "no");
    tmp.write("outside/secret.txt", "SECRET");
    tmp.write("root2/x.txt", "neighbour");  // a sibling whose name starts like root's
    fs::create_symlink(tmp / "outside/secret.txt", tmp / "root/link_out.txt");
    fs::create_symlink(tmp / "outside", tmp / "root/dir_out");
    fs::create_symlink("sub/a b.json", tmp / "root/link_in.json");
    root = tmp / "root";
  }
  test::TempDir tmp{"safe_path"};
  fs::path root;
};

TEST_F(SafePathTest, AcceptsFilesInside) {
  const ResolvedPath p = resolveBelowRoot(root, "index.html");
  ASSERT_TRUE(p.ok()) << pathRefusalName(p.refusal);
  EXPECT_EQ(p.path, fs::canonical(root / "index.html"));
  EXPECT_TRUE(resolveBelowRoot(root, "sub/a%20b.json").ok());   // decoded once
  EXPECT_TRUE(resolveBelowRoot(root, "sub//a%20b.json").ok());  // an empty component is nothing
  EXPECT_EQ(resolveBelowRoot(root, "./index.html").refusal, PathRefusal::Hidden);  // "." too
  // a symlink that stays inside is followed
  const ResolvedPath in = resolveBelowRoot(root, "link_in.json");
  ASSERT_TRUE(in.ok());
  EXPECT_EQ(in.path, fs::canonical(root / "sub/a b.json"));
}

TEST_F(SafePathTest, RefusesTraversal) {
  EXPECT_EQ(resolveBelowRoot(root, "../outside/secret.txt").refusal, PathRefusal::DotDot);
  EXPECT_EQ(resolveBelowRoot(root, "sub/../../outside/secret.txt").refusal, PathRefusal::DotDot);
  EXPECT_EQ(resolveBelowRoot(root, "%2e%2e/outside/secret.txt").refusal, PathRefusal::DotDot);
  EXPECT_EQ(resolveBelowRoot(root, "%2E%2E%2Foutside%2Fsecret.txt").refusal, PathRefusal::DotDot);
  EXPECT_EQ(resolveBelowRoot(root, "sub/..").refusal, PathRefusal::DotDot);
  // decoded exactly once: "%252e%252e" is the literal name "%2e%2e", which does not exist
  EXPECT_EQ(resolveBelowRoot(root, "%252e%252e/outside/secret.txt").refusal, PathRefusal::NotFound);
}

TEST_F(SafePathTest, RefusesAbsoluteBackslashNulAndBadEscapes) {
  const std::string abs = (tmp / "outside/secret.txt").string();
  EXPECT_EQ(resolveBelowRoot(root, abs).refusal, PathRefusal::Absolute);
  EXPECT_EQ(resolveBelowRoot(root, "%2Fetc%2Fpasswd").refusal, PathRefusal::Absolute);
  EXPECT_EQ(resolveBelowRoot(root, "/etc/passwd").refusal, PathRefusal::Absolute);
  EXPECT_EQ(resolveBelowRoot(root, "..\\outside\\secret.txt").refusal, PathRefusal::Backslash);
  EXPECT_EQ(resolveBelowRoot(root, "sub%5c..%5c..").refusal, PathRefusal::Backslash);
  EXPECT_EQ(resolveBelowRoot(root, "index.html%00.png").refusal, PathRefusal::NulByte);
  EXPECT_EQ(resolveBelowRoot(root, std::string("index.html\0.png", 15)).refusal,
            PathRefusal::NulByte);
  EXPECT_EQ(resolveBelowRoot(root, "index%2").refusal, PathRefusal::BadEncoding);
  EXPECT_EQ(resolveBelowRoot(root, "index%zz").refusal, PathRefusal::BadEncoding);
  EXPECT_EQ(resolveBelowRoot(root, "a%0Ab").refusal, PathRefusal::BadEncoding);
  EXPECT_EQ(resolveBelowRoot(root, ".hidden").refusal, PathRefusal::Hidden);
}

TEST_F(SafePathTest, RefusesSymlinksOutOfTheRoot) {
  EXPECT_EQ(resolveBelowRoot(root, "link_out.txt").refusal, PathRefusal::OutsideRoot);
  EXPECT_EQ(resolveBelowRoot(root, "dir_out/secret.txt").refusal, PathRefusal::OutsideRoot);
  EXPECT_EQ(resolveBelowRoot(root, "link_out.txt").httpStatus(), 403);
}

TEST_F(SafePathTest, SymlinkedRootServesItsTargetOnly) {
  // a root given through a symlink is the folder it points at
  fs::create_symlink(root, tmp / "root_link");
  const ResolvedPath p = resolveBelowRoot(tmp / "root_link", "index.html");
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p.path, fs::canonical(root / "index.html"));
  EXPECT_EQ(resolveBelowRoot(tmp / "root_link", "link_out.txt").refusal, PathRefusal::OutsideRoot);
  EXPECT_EQ(resolveBelowRoot(tmp / "root_link", "../outside/secret.txt").refusal,
            PathRefusal::DotDot);
}

TEST_F(SafePathTest, MissingFilesFoldersAndRoots) {
  EXPECT_EQ(resolveBelowRoot(root, "nope.html").refusal, PathRefusal::NotFound);
  EXPECT_EQ(resolveBelowRoot(root, "nope.html").httpStatus(), 404);
  EXPECT_EQ(resolveBelowRoot(root, "sub").refusal, PathRefusal::NotFound);  // no listings
  EXPECT_EQ(resolveBelowRoot(root, "").refusal, PathRefusal::NotFound);
  EXPECT_EQ(resolveBelowRoot(tmp / "no_root", "index.html").refusal, PathRefusal::NotFound);
}

TEST(SafePath, WithinComparesComponents) {
  EXPECT_TRUE(isWithin("/data/x", "/data"));
  EXPECT_TRUE(isWithin("/data", "/data"));
  EXPECT_FALSE(isWithin("/data2/x", "/data"));
  EXPECT_FALSE(isWithin("/", "/data"));
}

TEST(SafePath, PercentDecode) {
  EXPECT_EQ(percentDecode("a%20b+c"), "a b+c");
  EXPECT_EQ(percentDecode("%41%6a"), "Aj");
  EXPECT_FALSE(percentDecode("%4").has_value());
  EXPECT_FALSE(percentDecode("%").has_value());
  EXPECT_FALSE(percentDecode("%g1").has_value());
}

TEST(SafePath, ContentTypes) {
  EXPECT_EQ(contentTypeFor("a/index.html"), "text/html; charset=utf-8");
  EXPECT_EQ(contentTypeFor("app.js"), "text/javascript; charset=utf-8");
  EXPECT_EQ(contentTypeFor("s.CSS"), "text/css; charset=utf-8");
  EXPECT_EQ(contentTypeFor("l.json"), "application/json");
  EXPECT_EQ(contentTypeFor("i.png"), "image/png");
  EXPECT_EQ(contentTypeFor("i.jpg"), "image/jpeg");
  EXPECT_EQ(contentTypeFor("m.glb"), "model/gltf-binary");
  EXPECT_EQ(contentTypeFor("m.gltf"), "model/gltf+json");
  EXPECT_EQ(contentTypeFor("m.bin"), "application/octet-stream");
  EXPECT_EQ(contentTypeFor("d.exr"), "application/octet-stream");
  EXPECT_EQ(contentTypeFor("noext"), "application/octet-stream");
}

TEST(Loopback, AddressesAndHostHeaders) {
  EXPECT_TRUE(isLoopbackHost("127.0.0.1"));
  EXPECT_TRUE(isLoopbackHost("127.0.1.1"));
  EXPECT_TRUE(isLoopbackHost("::1"));
  EXPECT_TRUE(isLoopbackHost("localhost"));
  EXPECT_FALSE(isLoopbackHost("0.0.0.0"));
  EXPECT_FALSE(isLoopbackHost("::"));
  EXPECT_FALSE(isLoopbackHost("192.168.1.5"));
  EXPECT_FALSE(isLoopbackHost(""));
  EXPECT_FALSE(isLoopbackHost("no-such-host.invalid"));
  EXPECT_TRUE(isLoopbackHostHeader("localhost:8080"));
  EXPECT_TRUE(isLoopbackHostHeader("127.0.0.1:9000"));
  EXPECT_TRUE(isLoopbackHostHeader("[::1]:8080"));
  EXPECT_TRUE(isLoopbackHostHeader("LOCALHOST"));
  EXPECT_FALSE(isLoopbackHostHeader("evil.example:8080"));
  EXPECT_FALSE(isLoopbackHostHeader("127.0.0.1.evil.example"));
  EXPECT_FALSE(isLoopbackHostHeader(""));
  EXPECT_EQ(hostHeaderName("[::1]:80"), "::1");
}

}  // namespace
}  // namespace inet::studio
