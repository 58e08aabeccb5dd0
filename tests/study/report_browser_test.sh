#!/usr/bin/env bash
# The study report in a real browser:
#   report_browser_test.sh GRANASYM STUDY_DIR WORK_DIR
# Copies the small files of a finished study (STUDY_DIR: the tiny study of
# Study.paper_tiny_end_to_end), adds fixture figures and calibration results
# where the study has none (marked as fixtures in their texts), writes the
# report with `granasym study report` and renders index.html in headless
# Chromium at a desktop width and at 500 px (about the narrowest window
# headless Chromium makes). A script injected into a copy of the page
# records every image that did not load (naturalWidth 0) and every element
# that reaches past the viewport outside a scrolling container (a layout
# error); any of them fails the test, naming it. It also measures the page
# at 1280 px with every <details> closed, as a reader first sees it: at most
# base_px plus figure_px per figure drawn (below). Before the page was made
# short (tables folded, rows unwrapped) this test's page measured 16 900 px
# and the small-scale study's report (15 figures drawn) 61 000 px; after,
# 7 500 px and 20 000 px. It counts the tooltips of each inline SVG: every
# state point of a figure (each hypertext label gnuplot wrote into its SVG
# file) has a <title>. The findings come first, then the fitted parameters,
# then the figures. Two broken copies prove that the check fails: one with
# a truncated PNG, one with the stylesheet's horizontal scrolling of tables
# switched off.
set -euo pipefail
granasym="$1" study="$2" work="$3"
# The bound on the page's height at 1280 px (details closed).
base_px=9000 figure_px=1000

browser=""
for candidate in chromium chromium-browser; do
  if command -v "$candidate" >/dev/null 2>&1; then browser="$candidate"; break; fi
done
if [ -z "$browser" ]; then
  echo "FAIL: chromium is missing: run scripts/install_deps.sh (installs Debian's chromium)"
  exit 1
fi
[ -f "$study/study.toml" ] || { echo "FAIL: $study is not a study folder (no study.toml)"; exit 1; }

rm -rf "$work"
mkdir -p "$work"
dir="$work/study"
mkdir -p "$dir"
# The records and tables, not the HDF5 results (the report links, never reads them).
(cd "$study" && find . \( -name '*.toml' -o -name '*.csv' -o -name '*.tsv' -o -name '*.txt' \
   -o -name '*.png' -o -name '*.pdf' -o -name '*.svg' \) -not -path './samples/*' -print0 |
   xargs -0 cp --parents -t "$dir")

# hover_svg FILE: a wide SVG (gnuplot's svg terminal, as `study figures`
# draws them) whose five states carry hover labels (hypertext).
hover_svg() {
  gnuplot <<EOF
set terminal svg enhanced size 1800,500 mouse standalone
set output '$1'
set title 'test fixture'
\$states << EOD
1 0.84 "case nc100_psi90\\nreplicate 1\\nkind csl <b>not bold</b> & it's"
2 0.91 "case nc100_psi90\\nreplicate 2\\nkind csl"
3 0.14 "case nc200_psi90\\nreplicate 1\\nkind csl"
4 -0.76 "case nc500_psi90\\nreplicate 1\\nkind csl"
5 -0.96 "case nc1000_psi90\\nreplicate 1\\nkind csl"
EOD
plot sin(x) title 'sin', \$states using 1:2:3 with labels hypertext point pt 7 title 'states'
EOF
}

# Fixtures where the study has no figures (or none with hover labels) or
# calibration of its own.
fixtures=()
if [ ! -f "$dir/figures/index.tsv" ]; then
  fixtures+=(figures)
  mkdir -p "$dir/figures"
  # A wide image (wider than any viewport: the stylesheet must scale it), as
  # PNG and as SVG with a hover label on each of its states; a square one as
  # PNG only (the page carries it as a data URI).
  gnuplot -e "set terminal pngcairo size 1800,500; set output '$dir/figures/fixture_wide.png';
              set title 'test fixture'; plot sin(x)"
  gnuplot -e "set terminal pdfcairo; set output '$dir/figures/fixture_wide.pdf'; plot sin(x)"
  hover_svg "$dir/figures/fixture_wide.svg"
  gnuplot -e "set terminal pngcairo size 400,400; set output '$dir/figures/fixture_square.png';
              set title 'test fixture'; plot cos(x)"
  {
    printf 'stem\tfigure\ttitle\tcaption\n'
    printf 'fixture_wide\t16\tTest fixture: a wide figure <b>not bold</b>\tA fixture of the browser test (p < 100 kPa & "quotes"); %s\n' \
      "an_unbreakable_token_$(printf 'x%.0s' {1..300})"
    printf 'fixture_square\t8\tTest fixture: a square figure\tA fixture of the browser test.\n'
  } > "$dir/figures/index.tsv"
elif ! grep -qs 'gnuplot_svg.showHypertext(evt' "$dir"/figures/*.svg; then
  fixtures+=("figures/fixture_hover.svg")
  hover_svg "$dir/figures/fixture_hover.svg"
  printf 'fixture_hover\t16\tTest fixture: states with hover labels\tA fixture of the browser test.\n' \
    >> "$dir/figures/index.tsv"
fi
for model in hypoplastic_clay modified_cam_clay hypoplastic_sand; do
  folder="$dir/calibration/$model"
  [ -d "$folder" ] && continue
  fixtures+=("calibration/$model")
  mkdir -p "$folder"
  cat > "$folder/parameters.csv" <<'EOF'
parameter,value,std_error,ci95_low,ci95_high,status
lambda_star,0.0252,0.0011,0.0230,0.0274,fitted
n,0.686,0.004,0.678,0.694,fitted
phi_c_deg,29.9,,,,at_bound
kappa_star,0.004,0.01,-0.016,0.024,undetermined
EOF
  printf 'test fixture: phi_c_deg at its upper bound\ntest fixture: kappa_star is undetermined\n' \
    > "$folder/warnings.txt"
  {
    echo "test fixture: the summary of a fit, with one very long line:"
    printf 'residual%.0s ' {1..200}
    echo
  } > "$folder/summary.txt"
  printf '# test fixture\n[model]\nkind = "%s"\n' "$model" > "$folder/model.toml"
done
[ ${#fixtures[@]} -eq 0 ] || echo "fixtures (the study has none of its own): ${fixtures[*]}"

"$granasym" study report "$dir" | tee "$work/report.txt"
grep -q "report: $dir/index.html" "$work/report.txt" ||
  { echo "FAIL: the command did not say where index.html is"; exit 1; }
[ -s "$dir/report.md" ] || { echo "FAIL: no report.md"; exit 1; }
if grep -Eq '(src|href)="(https?:)?//' "$dir/index.html"; then
  echo "FAIL: index.html refers to something outside the study folder"; exit 1
fi

# The report opens with the findings (the paper's claims judged), before the overview.
first_section=$(grep -o '<h2 id="[^"]*"' "$dir/index.html" | head -1)
[[ "$first_section" == '<h2 id="findings'* ]] ||
  { echo "FAIL: the report opens with $first_section, not the findings"; exit 1; }

# The check, injected at the end of a copy of the page (the report itself has
# no scripts). Lines "check: ..." go into a <pre> once the page has loaded.
check_script='<script>
window.addEventListener("load", () => {
  const lines = [];
  // As a reader first sees the page: every <details> closed.
  lines.push("height " + document.documentElement.scrollHeight);
  // Each inline SVG: its hover groups and those with a non-blank <title>.
  const svgs = [...document.querySelectorAll("figure > svg")];
  svgs.forEach((svg, k) => {
    const groups = [...svg.querySelectorAll("g.hover")];
    const titled = groups.filter((g) => g.firstElementChild &&
        g.firstElementChild.tagName.toLowerCase() === "title" &&
        g.firstElementChild.textContent.trim() !== "");
    lines.push("tooltips " + k + " " + groups.length + " " + titled.length);
  });
  for (const d of document.querySelectorAll("details")) d.open = true;
  const images = [...document.images];
  for (const img of images) {
    if (!img.complete || img.naturalWidth === 0) lines.push("broken image: " + img.getAttribute("alt"));
  }
  const width = document.documentElement.clientWidth;
  const clips = (e) => {
    for (let a = e.parentElement; a; a = a.parentElement) {
      if (["auto", "scroll", "hidden", "clip"].includes(getComputedStyle(a).overflowX)) return true;
    }
    return false;
  };
  const name = (e) => e.tagName.toLowerCase() + (e.id ? "#" + e.id : "") +
      (e.className ? "." + String(e.className).replace(/ /g, ".") : "");
  // Only the outermost element past the edge: its descendants follow it.
  const outside = new Set();
  let elements = 0, errors = 0;
  for (const e of document.body.querySelectorAll("*")) {
    const r = e.getBoundingClientRect();
    if (r.width === 0 && r.height === 0) continue;
    ++elements;
    if (clips(e)) continue;
    // The box past the edge, or text running out of a box that does not scroll.
    const spills = e.clientWidth > 0 && getComputedStyle(e).overflowX === "visible" &&
                   e.scrollWidth > e.clientWidth + 1 && r.left + e.scrollWidth > width + 1;
    if (r.right > width + 1 || r.left < -1 || spills) {
      outside.add(e);
      if (outside.has(e.parentElement)) continue;
      if (++errors > 20) continue;
      const right = Math.round(Math.max(r.right, r.left + e.scrollWidth));
      lines.push("layout error: " + name(e) + " spans " + Math.round(r.left) + ".." + right +
                 " px, viewport " + width + " px: " +
                 (e.textContent || "").replace(/\s+/g, " ").trim().slice(0, 60));
    }
  }
  if (errors > 20) lines.push("layout error: and " + (errors - 20) + " more elements");
  if (document.documentElement.scrollWidth > width + 1) {
    lines.push("layout error: the page scrolls sideways (" +
               document.documentElement.scrollWidth + " px in " + width + " px)");
  }
  lines.push("done: " + svgs.length + " inline SVGs, " + images.length + " images, " + elements +
             " elements, viewport " + width + " px");
  const out = document.createElement("pre");
  out.id = "granasym-check";
  out.textContent = "\n" + lines.map((l) => "check: " + l).join("\n") + "\n";
  document.body.appendChild(out);
});
</script>'

# render PAGE WIDTH: prints the check lines of PAGE at a window WIDTH px wide.
render() {
  local page="$1" width="$2"
  local checked="${page%.html}.check.html"
  CHECK_SCRIPT="$check_script" awk '/<\/body>/ { print ENVIRON["CHECK_SCRIPT"] } { print }' \
    "$page" > "$checked"
  timeout 120 "$browser" --headless=new --no-sandbox --disable-gpu --disable-dev-shm-usage \
    --no-first-run --user-data-dir="$work/profile" --window-size="$width,900" \
    --virtual-time-budget=5000 --dump-dom "file://$checked" \
    2> "$work/browser-$width.log" | grep '^check: ' || true
}

# check PAGE: 0 when the page renders cleanly at both widths; prints the findings.
check() {
  local page="$1" failed=0 width lines
  for width in 1280 500; do
    lines=$(render "$page" "$width")
    if ! grep -q '^check: done' <<<"$lines"; then
      echo "  at $width px: the check did not run (see $work/browser-$width.log)"
      tail -5 "$work/browser-$width.log" | sed 's/^/    /'
      failed=1
      continue
    fi
    grep -Ev '^check: (height|tooltips) ' <<<"$lines" | sed "s/^check: /  at $width px: /"
    if grep -Eq '^check: (broken image|layout error)' <<<"$lines"; then failed=1; fi
    [ "$width" -ne 1280 ] || echo "$lines" > "$page.1280.txt"
  done
  return $failed
}

echo "the report:"
if ! check "$dir/index.html"; then
  echo "FAIL: the report has a missing image or a layout error (above)"; exit 1
fi
# One file: every figure is in the page (inline SVG, or a PNG as a data URI).
figures=$(grep -c '^<figure>' "$dir/index.html" || true)
# Figures without data are listed with the reason ("Not drawn: ...") and no image.
indexed=$(tail -n +2 "$dir/figures/index.tsv" | grep -vc 'Not drawn: ' || true)
[ "$figures" -eq "$indexed" ] ||
  { echo "FAIL: $figures figures in the page, $indexed drawn figures in figures/index.tsv"; exit 1; }
if grep -Eq '<img [^>]*src="[^d]' "$dir/index.html"; then
  echo "FAIL: index.html links an image file instead of carrying it"; exit 1
fi
if grep -Eq '<script|onmouse|onclick=|onload=' "$dir/index.html"; then
  echo "FAIL: index.html has a script or an event handler (from an SVG?)"; exit 1
fi
grep -q '&lt;b&gt;not bold' "$dir/index.html" || [ ! -f "$dir/figures/fixture_wide.png" ] ||
  { echo "FAIL: the fixture caption's markup was not escaped"; exit 1; }

# The answers first: the findings, then the fitted parameters, then the figures.
order=$(grep -o '<h2 id="[^"]*"' "$dir/index.html" | head -3 | sed 's/<h2 id="//; s/"$//' | tr '\n' ' ')
[[ "$order" == findings*' fitted-parameters figures ' ]] ||
  { echo "FAIL: the page opens with $order, not the findings, fitted parameters, figures"; exit 1; }

# The page's height at 1280 px, details closed.
height=$(sed -n 's/^check: height //p' "$dir/index.html.1280.txt")
bound=$((base_px + figure_px * figures))
echo "page height at 1280 px: $height px ($figures figures; bound $base_px + $figure_px per figure = $bound px)"
[ -n "$height" ] && [ "$height" -le "$bound" ] ||
  { echo "FAIL: the page is $height px high at 1280 px, more than $bound px"; exit 1; }

# Every state point of a figure has its tooltip: as many titled hover groups
# in the page as hypertext labels in the figure's SVG file (in index order).
k=0 hovered=0
while IFS=$'\t' read -r stem _; do
  [ -f "$dir/figures/$stem.svg" ] || continue
  labels=$({ grep -o 'gnuplot_svg.showHypertext(evt' "$dir/figures/$stem.svg" || true; } | wc -l)
  groups="" titled=""
  read -r groups titled < <(sed -n "s/^check: tooltips $k //p" "$dir/index.html.1280.txt") || true
  [ "${groups:-x}" = "$labels" ] && [ "${titled:-x}" = "$labels" ] ||
    { echo "FAIL: $stem.svg has $labels hover labels, the page ${groups:-no} groups, ${titled:-no} titled"; exit 1; }
  [ "$labels" -eq 0 ] || { hovered=$((hovered + 1)); echo "tooltips: $stem: each of its $labels states has one"; }
  k=$((k + 1))
done < <(tail -n +2 "$dir/figures/index.tsv")
[ "$hovered" -gt 0 ] || { echo "FAIL: no figure has hover labels to check"; exit 1; }

# The check must fail on a broken image: a copy of the study whose first
# figure with a PNG has no SVG and its PNG cut to 40 bytes and closed with
# an IEND chunk (so the report takes it, having checked the signature and
# the IEND chunk only, and the page carries a PNG that does not decode).
broken="$work/broken_image"
cp -r "$dir" "$broken"
rm -f "$broken"/index.html.*.txt
IFS=$'\t' read -r stem figure title < <(tail -n +2 "$dir/figures/index.tsv" |
  while IFS=$'\t' read -r s f t _; do
    [ -f "$dir/figures/$s.png" ] && { printf '%s\t%s\t%s\n' "$s" "$f" "$t"; break; }
  done)
label="Figure $figure: $title"
[[ "$figure" != Sec.* ]] || label="$figure: $title"
# As the page's DOM prints it.
label=$(sed 's/&/\&amp;/g; s/</\&lt;/g; s/>/\&gt;/g' <<<"$label")
rm -f "$broken/figures/$stem.svg"
head -c 40 "$dir/figures/$stem.png" > "$broken/figures/$stem.png"
# A PNG only truncated is refused by the report itself, as invalid.
"$granasym" study report "$broken" > /dev/null
grep -qF "figures/$stem.png\` is not a valid PNG" "$broken/report.md" ||
  { echo "FAIL: the report did not refuse figures/$stem.png truncated to 40 bytes"; exit 1; }
printf '\x00\x00\x00\x00IEND\xae\x42\x60\x82' >> "$broken/figures/$stem.png"
"$granasym" study report "$broken" > /dev/null
echo "a copy with figures/$stem.png cut to 40 bytes and an IEND chunk:"
check "$broken/index.html" > "$work/broken_image.txt" &&
  { cat "$work/broken_image.txt"; echo "FAIL: the check did not notice the broken image"; exit 1; }
grep 'broken image' "$work/broken_image.txt"
grep -qF "broken image: $label" "$work/broken_image.txt" ||
  { echo "FAIL: the check did not name $label"; exit 1; }

# ... and on a layout error: a copy without the horizontal scrolling of tables.
wide="$work/no_scrolling"
cp -r "$dir" "$wide"
sed -i 's/\.scroll{overflow-x:auto;/.scroll{overflow-x:visible;/' "$wide/index.html"
grep -q 'overflow-x:visible' "$wide/index.html" ||
  { echo "FAIL: the stylesheet has no .scroll rule to switch off"; exit 1; }
echo "a copy whose tables do not scroll:"
check "$wide/index.html" > "$work/no_scrolling.txt" &&
  { cat "$work/no_scrolling.txt"; echo "FAIL: the check did not notice tables wider than the page"; exit 1; }
echo "  $(grep -c 'layout error' "$work/no_scrolling.txt") layout errors, e.g.:"
grep -m 3 'layout error: div.scroll' "$work/no_scrolling.txt" ||
  { echo "FAIL: the check did not name a table's container"; exit 1; }

echo "PASS: $figures figures (inline SVG or PNG data URIs) and every table render inside the viewport at 1280 and 500 px; the page is $height px high at 1280 px (bound $bound), answers first, every hover label a tooltip; a truncated PNG and unscrolled tables are caught"
