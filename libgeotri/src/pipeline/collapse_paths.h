#pragma once
// What the edges of a decimated mesh are on the fine mesh: a path of fine vertices per edge, kept through halfedge
// collapses. Collapsing v0 into v1 drags every edge (v0, w) along the collapsed edge, so that the new edge (v1, w) is
// the path from v1 to v0 followed by the path from v0 to w. These paths may overlap, but they keep the homotopy class
// of each edge on the fine surface with the surviving vertices taken out, which is what a geodesic of the edge must
// keep for the triangulation to be the decimated one (geodesic::straighten_path).
//
// A collapse must cost little, so a path is a node of a tree that is never copied: one fine edge, or two paths one
// after the other. Paths are written out only at the end, for the edges that are left.

#include <vector>

namespace geotri::detail {

class CollapsePaths {
public:
    /// A path, or -1 for the single fine edge between the ends of the edge that holds it.
    using Ref = int;
    static constexpr Ref k_single_edge = -1;

    /// `ref`, held by an edge between fine vertices a and b, as a path from a to b.
    Ref oriented(Ref ref, int a, int b) {
        if (ref == k_single_edge) {
            nodes_.push_back({a, b, -1, -1});
            return 2 * static_cast<Ref>(nodes_.size() - 1);
        }
        return first(ref) == a ? ref : ref ^ 1;
    }

    /// The path `to` followed by `from`; `to` must end where `from` starts.
    Ref join(Ref to, Ref from) {
        nodes_.push_back({first(to), last(from), to, from});
        return 2 * static_cast<Ref>(nodes_.size() - 1);
    }

    /// The fine vertices of `ref` from a to b, without steps straight back (…, x, y, x → …, x: y is a removed
    /// vertex, so going there and back changes no class).
    std::vector<int> vertices(Ref ref, int a, int b) {
        std::vector<int> path;
        std::vector<Ref> stack{oriented(ref, a, b)};
        while (!stack.empty()) {
            const Ref r = stack.back();
            stack.pop_back();
            const Node& node = nodes_[static_cast<std::size_t>(r / 2)];
            const bool reversed = (r & 1) != 0;
            if (node.left < 0) {
                append(path, reversed ? node.last : node.first);
                append(path, reversed ? node.first : node.last);
            } else if (!reversed) {
                stack.push_back(node.right);
                stack.push_back(node.left);
            } else {
                stack.push_back(node.left ^ 1);
                stack.push_back(node.right ^ 1);
            }
        }
        return path;
    }

private:
    struct Node {
        int first, last;  // fine vertices at its ends
        Ref left, right;  // the two halves, or -1 for a single fine edge
    };

    int first(Ref r) const {
        const Node& n = nodes_[static_cast<std::size_t>(r / 2)];
        return (r & 1) ? n.last : n.first;
    }
    int last(Ref r) const {
        const Node& n = nodes_[static_cast<std::size_t>(r / 2)];
        return (r & 1) ? n.first : n.last;
    }
    static void append(std::vector<int>& path, int x) {
        if (!path.empty() && path.back() == x) return;
        if (path.size() >= 2 && path[path.size() - 2] == x) {
            path.pop_back();
            return;
        }
        path.push_back(x);
    }

    std::vector<Node> nodes_;
};

}  // namespace geotri::detail
