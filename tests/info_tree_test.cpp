// `csgray info`'s counts and tree on a DAG. The evaluator builds trees (every use of a module
// or of children() is evaluated again), but csg's nodes are shared pointers and the writer
// promises DAGs: counts of the tree as written out, each shared node printed once with an
// "id" and as {"ref": id} afterwards. These DAGs are built by hand from an evaluated part.
#include <gtest/gtest.h>

#include <cstdint>
#include <nlohmann/json.hpp>

#include "io/Evaluate.h"
#include "io/TreeJson.h"

namespace {

io::Model cubeAt123() {
    io::EvaluateResult r = io::evaluateString("translate([1, 2, 3]) cube(2);\n", "post.scad");
    EXPECT_TRUE(r.ok());
    return std::move(*r.model);
}

nlohmann::json writeTree(const io::Model& model, const csg::Node& root, io::NodeCounts* counts) {
    io::TreeWriter writer(model);
    *counts = writer.count(root);
    std::string out;
    csg::JsonWriter json(out);
    writer.write(json, root);
    return nlohmann::json::parse(out);
}

TEST(InfoTree, ASharedSubtreeIsWrittenOnceAndCountedPerUse) {
    const io::Model model = cubeAt123();
    const csg::NodePtr post = model.root;
    ASSERT_TRUE(post && post->op == csg::Op::Leaf);
    // (post u post) - post: three uses of one leaf.
    const csg::NodePtr dag = csg::subtract(csg::unite(post, post), post);
    io::NodeCounts counts;
    const nlohmann::json tree = writeTree(model, *dag, &counts);

    EXPECT_EQ(counts.leaves.at("cube"), 3u);
    EXPECT_EQ(counts.leafTotal(), 3u);
    EXPECT_EQ(counts.unions, 1u);
    EXPECT_EQ(counts.differences, 1u);
    EXPECT_EQ(counts.intersections, 0u);
    EXPECT_EQ(counts.transformed, 3u);  // the translate is the leaf's, once per use
    EXPECT_EQ(counts.total(), 5u);

    EXPECT_EQ(tree.at("op"), "difference");
    EXPECT_FALSE(tree.contains("id")) << "used once";
    const nlohmann::json& united = tree.at("children")[0];
    EXPECT_EQ(united.at("op"), "union");
    EXPECT_FALSE(united.contains("id"));
    const nlohmann::json& first = united.at("children")[0];
    EXPECT_EQ(first.at("id"), 0);
    EXPECT_EQ(first.at("op"), "cube");
    EXPECT_EQ(first.at("transform")[1][3], 2.0);  // row y, translation column
    EXPECT_EQ(first.at("source"), "post.scad:1:22");
    EXPECT_EQ(united.at("children")[1], nlohmann::json({{"ref", 0}}));
    EXPECT_EQ(tree.at("children")[1], nlohmann::json({{"ref", 0}}));
}

TEST(InfoTree, ASubtreeUsedAMillionTimesStaysSmall) {
    const io::Model model = cubeAt123();
    csg::NodePtr dag = model.root;
    for (int level = 0; level < 20; ++level) dag = csg::unite(dag, dag);
    io::TreeWriter writer(model);
    const io::NodeCounts counts = writer.count(*dag);
    EXPECT_EQ(counts.leafTotal(), uint64_t(1) << 20);
    EXPECT_EQ(counts.unions, (uint64_t(1) << 20) - 1);
    std::string out;
    csg::JsonWriter json(out);
    writer.write(json, *dag);
    // 21 distinct nodes: each level's union written once, its second child a {"ref"}. Ids go
    // in writing order, so the root's first child, written first, is id 0.
    EXPECT_LT(out.size(), 21u * 400) << out.size() << " bytes";
    EXPECT_EQ(nlohmann::json::parse(out).at("children")[1], nlohmann::json({{"ref", 0}}));
}

TEST(InfoTree, CountsSaturateInsteadOfWrapping) {
    const io::Model model = cubeAt123();
    csg::NodePtr dag = model.root;
    for (int level = 0; level < 70; ++level) dag = csg::unite(dag, dag);  // 2^70 leaves
    io::TreeWriter writer(model);
    const io::NodeCounts counts = writer.count(*dag);
    EXPECT_EQ(counts.leafTotal(), UINT64_MAX);
    EXPECT_EQ(counts.transformed, UINT64_MAX);
    EXPECT_EQ(counts.total(), UINT64_MAX);
}

}  // namespace
