// Which far form draws a tree: its billboard, or a point where its sphere is too small on
// screen for the billboard to show more than an average colour. The billboard and point
// passes both decide with this one function, so a tree is always exactly one of the two.
uniform float treeScreenScale;   // pixels one metre spans at one metre's distance
uniform float treePointDiameter; // pixels: a tree's sphere under this diameter is a point

// `treePosition` relative to the trees' origin, `origin` that origin minus the camera,
// `sphere` the species' impostor sphere; all of it computed here, `precise`, so that the two
// programs cannot round it differently.
bool treeIsPoint(vec3 treePosition, vec3 origin, vec4 sphere) {
    precise vec3 centre = treePosition + origin + sphere.xyz;
    // diameter / distance < limit, without the division.
    precise float diameter = 2.0 * sphere.w * treeScreenScale;
    precise float limit = treePointDiameter * length(centre);
    return diameter < limit;
}
