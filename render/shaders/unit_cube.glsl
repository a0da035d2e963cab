// The 36 corner indices of a unit cube's 12 triangles (corner i: x = bit 0, y = bit 1, z = bit 2).
// Triangles wind counter-clockwise seen from outside, so culling front faces leaves exactly the back
// faces: one fragment per pixel the box covers, also when the eye is inside the box.
const int CUBE[36] = int[36](0, 6, 2, 0, 4, 6, 1, 7, 5, 1, 3, 7, 0, 5, 4, 0, 1, 5,
                             2, 7, 3, 2, 6, 7, 0, 3, 1, 0, 2, 3, 4, 7, 6, 4, 5, 7);

vec3 cubeCorner(int vertex) {
    int corner = CUBE[vertex];
    return vec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
}
