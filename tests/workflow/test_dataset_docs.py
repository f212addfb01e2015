"""docs/datasets.md lists what the study writes: every dataset kind, every coordinate and
variable with its units and meaning, as the tiny study's files hold them."""

import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "workflow" / "scripts" / "dataset_docs.py"


def test_the_datasets_page_is_the_studys(study):
    root, _ = study
    made = subprocess.run([sys.executable, str(SCRIPT), str(root / "results")], check=True,
                          capture_output=True, text=True).stdout
    page = (REPO / "docs" / "datasets.md").read_text(encoding="utf-8")
    assert made.rstrip() == page.rstrip(), (
        "docs/datasets.md is not what the study writes: remake it with "
        "`python workflow/scripts/dataset_docs.py results > docs/datasets.md` "
        "after the tiny study")
