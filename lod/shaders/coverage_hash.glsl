// A fixed number in [0, 1) per key: a point under a pixel is kept when it is below the point's
// area, so that a field of such points covers on average what their objects would.
float coverageHash(uint i) {
    i ^= i >> 16;
    i *= 0x7feb352du;
    i ^= i >> 15;
    i *= 0x846ca68bu;
    i ^= i >> 16;
    return float(i >> 8) * (1.0 / 16777216.0);
}
