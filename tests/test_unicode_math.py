"""Inline LaTeX shown in a terminal: verify.unicode_math.plain."""
import pytest

from verify.unicode_math import plain


@pytest.mark.parametrize("tex, text", [
    (r"With $\dot{\phi}_0 = 25.7$, $\theta_0 = 1.205$", "With φ̇₀ = 25.7, θ₀ = 1.205"),
    (r"$\sqrt{980} = 31.305$", "√(980) = 31.305"),
    (r"$\psi + \phi \approx \text{constant}$", "ψ + φ ≈ constant"),
    (r"$t \leftarrow t\sqrt{g/R}$", "t ← t√(g/R)"),
    (r"$\dot{\psi}_0^{2} = g/(k+1)$", "ψ̇₀² = g/(k+1)"),
    (r"precess \mathbf{L} at $\dot\phi$", "precess L at φ̇"),
    (r"$\lvert x \rvert$, $\omega_{3}$, $p_{\phi}$", "| x |, ω₃, p_φ"),
    ("no math here: 5 $ and more", "no math here: 5 $ and more"),
])
def test_plain(tex, text):
    assert plain(tex) == text


def test_the_figure_texts_show_no_tex():
    from verify.paper_figures import figure_list, list_text

    text = list_text(figure_list())
    assert "$" not in text and "\\" not in text
