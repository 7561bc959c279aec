// Which far form draws a tree: its billboard, or a point where its sphere is too small on
// screen for the billboard to show more than an average colour. The billboard and point
// passes both decide with this one function, so a tree is always exactly one of the two.
uniform float treeScreenScale;   // pixels one metre spans at one metre's distance
uniform float treePointDiameter; // pixels: a tree's sphere under this diameter is a point

bool treeIsPoint(vec3 centre, float radius) {
    // diameter / distance < limit, without the division.
    precise float diameter = 2.0 * radius * treeScreenScale;
    precise float limit = treePointDiameter * length(centre);
    return diameter < limit;
}
