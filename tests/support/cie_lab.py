"""CIE L*a*b* -> XYZ (CIE 15:2004), for the example scripts that feed tristim XYZ from published
L*a*b* tables. Written out here, not taken from tristim, so the scripts check tristim against an
independent conversion."""

D50 = (96.4212, 100.0, 82.5188)   # tristim's whites::D50 (CIE 15 / colour-science)
D65 = (95.0489, 100.0, 108.8840)  # tristim's whites::D65


def lab_to_xyz(lab, white=D50):
    """XYZ (the white's scale, Y = 100) of one L*a*b* triple relative to `white`."""
    L, a, b = lab
    fy = (L + 16) / 116
    fx, fz = fy + a / 500, fy - b / 200
    inv = lambda t: t ** 3 if t > 6 / 29 else 3 * (6 / 29) ** 2 * (t - 4 / 29)
    return [white[0] * inv(fx), white[1] * inv(fy), white[2] * inv(fz)]
