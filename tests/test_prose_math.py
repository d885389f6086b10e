"""The page's prose math (verify.report.prose_math): ASCII names set as symbols, code and anchors left alone."""
import html as html_lib
import re
from pathlib import Path

import pytest

from verify.report.prose_math import typeset_prose, typeset_text

PAGE = Path(__file__).parent.parent / "reports" / "report.html"


@pytest.mark.parametrize("ascii_, typeset", [
    ("theta -&gt; 0", "θ → 0"), ("phidot0 = 25.7, theta0 = 1.205", "φ̇₀ = 25.7, θ₀ = 1.205"),
    ("28.0 s^-1 and 980 s^-2", "28.0 s⁻¹ and 980 s⁻²"), ("largest mu_req", "largest μ<sub>req</sub>"),
    ("psidot0^2 = g/(k+1)", "ψ̇₀² = g/(k+1)"), ("omega3 oscillates", "ω₃ oscillates"), ("g/phidot^2", "g/φ̇²"),
    ("dL/dtheta", "dL/dθ"), ("Delta theta = +0.0002", "Δθ = +0.0002"), ("x &lt;= 3", "x ≤ 3"),
    ("I1 = 0.4993", "I₁ = 0.4993"), ("mu_req; phidot0.", "μ<sub>req</sub>; φ̇₀."), ("the end of theta.", "the end of θ."), ("sqrt(g/R)", "√(g/R)"), ("omega_dot_i", "ω̇<sub>i</sub>"),
])
def test_names_become_symbols(ascii_, typeset):
    assert typeset_text(ascii_) == typeset


@pytest.mark.parametrize("kept", ["ring+air-drag", "verify/claims/paper.md", "the disk rolls", "philosophy",
                                  "epsilons", "x.theta", "mp:128", "&pi; &mu;", "mu.csv", "theta.png", "run-mu.csv",
                                  "https://example.org/theta/pi?mu=1"])
def test_other_words_are_left_alone(kept):
    assert typeset_text(kept) == kept


def test_code_math_and_attributes_are_untouched():
    page = ('<h2 id="the-theta-0-spin-down">The theta -&gt; 0 spin-down</h2><code>mu_req</code>'
            '<math><mi>theta</mi></math><pre>theta</pre><a title="phidot">phidot</a>')
    assert typeset_prose(page) == ('<h2 id="the-theta-0-spin-down">The θ → 0 spin-down</h2><code>mu_req</code>'
                                   '<math><mi>theta</mi></math><pre>theta</pre><a title="phidot">φ̇</a>')


def test_the_page_s_prose_has_no_ascii_math_left():
    """Negative control included: the same check finds the names in the page's raw texts."""
    body = re.sub(r"<(math|code|pre|script|style)\b.*?</\1>", "", PAGE.read_text(encoding="utf-8"), flags=re.S)
    visible = html_lib.unescape(re.sub(r"<[^>]+>", " ", body))
    pattern = r"\b(?:theta|phi|psi|omega|alpha)(?:dot)?\d?\b|\bmu_req\b| -> |\bs\^-1\b"
    assert re.findall(pattern, visible) == []
    assert re.findall(pattern, "the theta -> 0 limit needs mu_req = 0.3 at 28 s^-1")
