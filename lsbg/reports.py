"""Reports: parameterised notebooks executed by papermill, rendered to one HTML file.

The reports are ``lsbg/notebooks/{name}.ipynb``, package data (:data:`NOTEBOOK_DIR`;
another folder can be given). Each has
a cell tagged ``parameters``; :func:`render_report` injects the caller's
values, runs the notebook with the current Python's kernel in the caller's
directory, and converts the executed notebook into a self-contained HTML file:
no code, figures embedded as base64 PNG, no script loaded from the network.
Relative paths given as parameters are resolved against the caller's
directory before injection, so they work wherever the kernel runs.

The :class:`Report` helper is for the notebooks themselves: numbered figures
with captions below them, numbered tables rendered as HTML, computed text as
Markdown.
"""

from __future__ import annotations

import logging
import os
import shutil
from pathlib import Path

import lsbg
from lsbg.files import remove_stale_temporaries, temporary_beside
from lsbg.files import write_text_atomically
from lsbg.tables.style import format_table

__all__ = ["NOTEBOOK_DIR", "PATH_PARAMETER_SUFFIXES", "ReportError", "notebook_path",
           "available_reports", "notebook_parameters", "parse_parameter",
           "resolve_parameters", "render_report", "notebook_to_html", "Report",
           "provenance", "format_table", "REPORT_STYLE"]

log = logging.getLogger(__name__)

#: Default folder of the report notebooks: ``notebooks`` of the package (package data).
NOTEBOOK_DIR = Path(__file__).resolve().parent / "notebooks"

#: A parameter whose name is one of these or ends in ``_<suffix>`` holds a path
#: or a list of paths; relative ones are made absolute before injection.
PATH_PARAMETER_SUFFIXES = ("run", "runs", "file", "files", "geometry", "dir", "dirs")

# The lab template without the scripts it loads from a CDN (require.js,
# MathJax, mermaid): the reports use neither widgets nor LaTeX.
_TEMPLATE_NAME = "lsbg_report.html.j2"
#: The reports' own style: tables in one compact style that wraps headers, the
#: finding box that opens each report. Selectors are more specific than
#: JupyterLab's, whose stylesheet comes later.
REPORT_STYLE = """
.jp-RenderedHTMLCommon table.lsbg-table { font-size: 13px; table-layout: auto; margin: 0.3em 0 1em; }
.jp-RenderedHTMLCommon table.lsbg-table th { white-space: normal; vertical-align: bottom;
  text-align: left; border-bottom: 1px solid #888; padding: 0.3em 0.5em; max-width: 11em; }
.jp-RenderedHTMLCommon table.lsbg-table td { padding: 0.25em 0.5em; }
.jp-RenderedHTMLCommon table.lsbg-table td.num { text-align: right; font-variant-numeric: tabular-nums;
  white-space: nowrap; }
.jp-RenderedHTMLCommon table.lsbg-table td.text { text-align: left; }
.jp-RenderedHTMLCommon table.lsbg-table tbody tr:nth-child(odd) { background: #f5f6f8; }
.jp-RenderedHTMLCommon div.lsbg-finding { border-left: 5px solid #2a6fb0; background: #eef4fa;
  padding: 0.6em 1.1em; margin: 0.4em 0 1em; font-size: 15px; }
.jp-RenderedHTMLCommon div.lsbg-finding p, .jp-RenderedHTMLCommon div.lsbg-finding li { margin: 0.3em 0; }
.jp-RenderedHTMLCommon div.lsbg-finding h2 { margin-top: 0.2em; }
.jp-RenderedHTMLCommon a.lsbg-csv { font-size: 13px; }
"""

# The lab template without the scripts it loads from a CDN (require.js,
# MathJax, mermaid): the reports use neither widgets nor LaTeX.
_TEMPLATE_NAME = "lsbg_report.html.j2"
_TEMPLATE = """{%- extends 'index.html.j2' -%}
{%- block html_head_js_requirejs -%}{%- endblock html_head_js_requirejs -%}
{%- block html_head_js_mathjax -%}{%- endblock html_head_js_mathjax -%}
{%- block html_head_js_mermaidjs -%}{%- endblock html_head_js_mermaidjs -%}
{%- block extra_css -%}<style type="text/css">""" + REPORT_STYLE + """</style>{%- endblock extra_css -%}
"""


class ReportError(RuntimeError):
    """A report notebook failed while executing; no HTML was written."""


# -------------------------------------------------------------- notebooks
def notebook_path(name, notebook_dir=None) -> Path:
    """The notebook of report ``name``.

    Parameters
    ----------
    name : str
        Report name, e.g. ``'paper'``.
    notebook_dir : str or os.PathLike, optional
        Folder of the notebooks (default :data:`NOTEBOOK_DIR`).

    Raises
    ------
    ValueError
        If there is no ``{name}.ipynb`` (the message lists the reports).
    """
    folder = Path(notebook_dir) if notebook_dir is not None else NOTEBOOK_DIR
    path = folder / f"{name}.ipynb"
    if not path.is_file():
        raise ValueError(f"report {name!r}: no notebook {path} (available: "
                         f"{', '.join(available_reports(folder)) or 'none'})")
    return path


def available_reports(notebook_dir=None) -> list:
    """Names of the report notebooks in ``notebook_dir`` (default :data:`NOTEBOOK_DIR`)."""
    folder = Path(notebook_dir) if notebook_dir is not None else NOTEBOOK_DIR
    return sorted(p.stem for p in folder.glob("*.ipynb")) if folder.is_dir() else []


def notebook_parameters(path) -> dict:
    """Parameters of a notebook's ``parameters`` cell with their defaults.

    Returns
    -------
    dict
        Name -> default value as written in the cell (a string of Python).
    """
    import papermill

    return {name: info["default"] for name, info in papermill.inspect_notebook(str(path)).items()}


def parse_parameter(text):
    """Split ``KEY=VALUE`` and read VALUE as YAML (``[a.nc, b.nc]`` is a list).

    An empty VALUE is the empty string (not YAML's null).

    Returns
    -------
    (str, object)

    Raises
    ------
    ValueError
        If there is no ``=`` or no key, or VALUE is not valid YAML.
    """
    import yaml

    key, sep, value = text.partition("=")
    key = key.strip()
    if not sep or not key.isidentifier():
        raise ValueError(f"--param {text!r}: must be KEY=VALUE with KEY a parameter name")
    if not value.strip():
        return key, ""
    try:
        return key, yaml.safe_load(value)
    except yaml.YAMLError as err:
        raise ValueError(f"--param {text!r}: VALUE is not valid YAML ({err})") from None


def _is_path_parameter(name):
    return any(name == s or name.endswith("_" + s) for s in PATH_PARAMETER_SUFFIXES)


def resolve_parameters(parameters, cwd=None) -> dict:
    """Path parameters as the kernel sees them: relative to ``cwd`` where inside it.

    The notebook runs in ``cwd``, so a path inside it stays relative (and so
    does everything the report prints: the same study run in two directories
    gives the same report); a path outside it becomes absolute.

    Parameters
    ----------
    parameters : dict
        Notebook parameters; those named as in :data:`PATH_PARAMETER_SUFFIXES`
        hold a path or a list of paths (``""`` stays ``""``).
    cwd : str or os.PathLike, optional
        Directory relative paths refer to (default: the current one).

    Returns
    -------
    dict
        A copy with normalised paths (as strings, POSIX separators).
    """
    base = Path(os.path.abspath(cwd if cwd is not None else os.getcwd()))

    def normalised(value):
        if isinstance(value, os.PathLike):
            value = os.fspath(value)
        if isinstance(value, str):
            if not value.strip():
                return value
            path = Path(os.path.normpath(base / value))
            return (path.relative_to(base).as_posix() if path.is_relative_to(base)
                    else path.as_posix())
        if isinstance(value, (list, tuple)):
            return [normalised(v) for v in value]
        return value

    return {key: normalised(value) if _is_path_parameter(key) else value
            for key, value in (parameters or {}).items()}


def _strip_stderr(nb):
    """Remove stderr streams (library warnings) from the outputs; return them."""
    messages = []
    for cell in nb.cells:
        if cell.get("cell_type") != "code":
            continue
        kept = []
        for output in cell.get("outputs", []):
            if output.get("output_type") == "stream" and output.get("name") == "stderr":
                messages.append(output.get("text", ""))
            else:
                kept.append(output)
        cell["outputs"] = kept
    return messages


def notebook_to_html(nb) -> str:
    """An executed notebook as self-contained HTML without its code.

    Parameters
    ----------
    nb : nbformat.NotebookNode

    Returns
    -------
    str
        HTML of the JupyterLab template with the inputs and prompts left out,
        images embedded, and no ``<script src=...>`` from the network.
    """
    from jinja2 import DictLoader
    from nbconvert import HTMLExporter

    exporter = HTMLExporter(template_name="lab",
                            extra_loaders=[DictLoader({_TEMPLATE_NAME: _TEMPLATE})],
                            exclude_input=True, exclude_input_prompt=True,
                            exclude_output_prompt=True, embed_images=True)
    exporter.template_file = _TEMPLATE_NAME
    body, _ = exporter.from_notebook_node(nb)
    return body


def render_report(name, out_html, parameters=None, notebook_dir=None, cwd=None,
                  kernel_name="python3", timeout=None, kernel_manager=None) -> Path:
    """Execute a report notebook with papermill and write it as one HTML file.

    Parameters
    ----------
    name : str
        Report name: the notebook ``{name}.ipynb``.
    out_html : str or os.PathLike
        HTML file to write (atomically: a temporary file renamed at the end);
        its folder is created if needed.
    parameters : dict, optional
        Values for the notebook's ``parameters`` cell; path parameters
        (:data:`PATH_PARAMETER_SUFFIXES`) are given to the notebook relative to
        ``cwd`` where inside it (:func:`resolve_parameters`).
    notebook_dir : str or os.PathLike, optional
        Folder of the notebooks (default :data:`NOTEBOOK_DIR`).
    cwd : str or os.PathLike, optional
        Working directory of the kernel (default: the current one).
    kernel_name : str, default 'python3'
        Jupyter kernel; ``python3`` runs the current Python interpreter.
    timeout : float, optional
        Limit per cell [s] (none by default).
    kernel_manager : type, optional
        The kernel's manager (a :class:`jupyter_client.manager.AsyncKernelManager`
        subclass; default: papermill's own), e.g. the workflow job server's
        (:func:`lsbg.cli.job_server.forked_kernel_manager`).

    Returns
    -------
    pathlib.Path
        The HTML file.

    Raises
    ------
    ValueError
        Unknown report or a parameter the notebook does not declare.
    ReportError
        If the notebook fails; the message names the cell and the error, and
        nothing is written.
    """
    import nbformat
    import papermill

    notebook = notebook_path(name, notebook_dir)
    parameters = dict(parameters or {})
    declared = notebook_parameters(notebook)
    unknown = sorted(set(parameters) - set(declared))
    if unknown:
        raise ValueError(f"report {name!r}: unknown parameter(s) {unknown} "
                         f"(declared: {sorted(declared)})")
    cwd = Path(cwd) if cwd is not None else Path.cwd()
    parameters = resolve_parameters(parameters, cwd)
    out_html = Path(out_html)
    out_html.parent.mkdir(parents=True, exist_ok=True)
    # ipykernel warns on every start that its local TCP sockets are unencrypted.
    # (and logs an ERROR for the interrupt jupyter_client sends before shutdown).
    quiet = ["--IPKernelApp.log_level=CRITICAL"] if kernel_name == "python3" else []
    # The executed notebook goes beside the report, where a rerun removes what
    # a killed run left (lsbg.files.remove_stale_temporaries), not into /tmp.
    remove_stale_temporaries(out_html)
    work = temporary_beside(out_html, "tmp", directory=True)
    try:
        executed = work / f"{name}.ipynb"
        manager = {} if kernel_manager is None else {"kernel_manager_class": kernel_manager}
        try:
            papermill.execute_notebook(
                str(notebook), str(executed), parameters=parameters, kernel_name=kernel_name,
                cwd=str(cwd), progress_bar=False, log_output=False,
                request_save_on_cell_execute=False, execution_timeout=timeout,
                extra_arguments=quiet, **manager)
        except papermill.PapermillExecutionError as err:
            raise ReportError(f"report {name!r}: notebook {notebook.name} failed in cell "
                              f"{err.exec_count}: {err.ename}: {err.evalue}") from None
        except Exception as err:  # kernel died, timeout, ...
            raise ReportError(f"report {name!r}: notebook {notebook.name} could not be "
                              f"executed: {type(err).__name__}: {err}") from err
        nb = nbformat.read(executed, as_version=4)
        for cell in nb.cells:
            # papermill gives its parameters cell a random id; keep the HTML reproducible
            if "injected-parameters" in cell.get("metadata", {}).get("tags", []):
                cell["id"] = "injected-parameters"
        for message in _strip_stderr(nb):
            log.warning("report %s: %s", name, message.strip())
        html = notebook_to_html(nb)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return write_text_atomically(out_html, html)


# ------------------------------------------------------ inside a notebook
def provenance(files, extra=None) -> str:
    """Markdown listing the input files, the lsbg version and the time.

    Parameters
    ----------
    files : dict
        ``{description: path or list of paths}``; empty values are listed as
        "not given".
    extra : dict, optional
        More ``{name: value}`` lines (e.g. statistics settings).

    Returns
    -------
    str
    """
    import datetime

    lines = []
    for description, value in files.items():
        paths = [value] if isinstance(value, (str, os.PathLike)) else list(value or [])
        paths = [str(p) for p in paths if str(p).strip()]
        shown = ", ".join(f"`{p}`" for p in paths) if paths else "not given"
        lines.append(f"- {description}: {shown}")
    for name, value in (extra or {}).items():
        lines.append(f"- {name}: {value}")
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    lines.append(f"- computed with lsbg {lsbg.__version__} on {now}")
    return "\n".join(lines)


class Report:
    """Numbered figures and tables with captions, for a report notebook.

    Parameters
    ----------
    name : str, optional
        The report's name; names the CSV files its tables attach
        (``{name}-table-{n}.csv``).
    dpi : float, default 100
        Resolution of the embedded PNG figures.

    Examples
    --------
    In a notebook cell::

        rep = Report("paper")
        rep.finding("The SBG fluctuates less ...", table)
        rep.figure(fig, "Gear speed against time.")
        rep.table(df, "Simulated means and Eq. 12-13.", formats={"error": "{:.3f}"})
    """

    def __init__(self, name="report", dpi=100):
        self.name = name
        self.dpi = dpi
        self.figures = 0
        self.tables = 0

    @staticmethod
    def _display(*objects):
        from IPython.display import display

        display(*objects)

    def _caption(self, caption):
        from IPython.display import Markdown

        self.figures += 1
        return Markdown(f"**Figure {self.figures}.** {caption}")

    def markdown(self, text):
        """Show computed Markdown text."""
        from IPython.display import Markdown

        self._display(Markdown(text))

    def finding(self, text, table=None, caption="", formats=None, digits=4, headers=None):
        """Show the report's finding: a boxed summary (class ``lsbg-finding``) at its top.

        Parameters
        ----------
        text : str
            Markdown: what was compared, the answer with its numbers, where it holds.
        table : pandas.DataFrame, optional
            At most one small table, in the reports' table style
            (:func:`lsbg.tables.style.format_table`), after the text; not numbered.
        caption : str
            Shown above the table.
        formats, digits, headers
            As for :meth:`table`.
        """
        import mistune
        from IPython.display import HTML

        body = mistune.html(text)
        if table is not None:
            body += (f"<p><i>{_escape(caption)}</i></p>" if caption else "")
            body += format_table(table, formats, digits=digits, headers=headers)
        self._display(HTML(f'<div class="lsbg-finding">{body}</div>'))

    def figure(self, fig, caption):
        """Show a figure as an embedded PNG with "Figure n." and the caption below."""
        self.figures_side_by_side([fig], caption)

    def figures_side_by_side(self, figs, caption):
        """Show several figures in one row (wrapping if narrow) with one caption."""
        from IPython.display import HTML

        from lsbg.figures.base import figure_png  # (matplotlib only in lsbg.figures)

        style = (f"max-width:{100 / len(figs):.0f}%; min-width:320px; height:auto"
                 if len(figs) > 1 else "max-width:100%; height:auto")
        images = "".join(_img(figure_png(fig, self.dpi), caption, style) for fig in figs)
        self._display(HTML(f'<div style="display:flex; flex-wrap:wrap; gap:8px">{images}</div>'),
                      self._caption(caption))

    def table(self, df, caption, formats=None, index=False, digits=4, headers=None, full=None):
        """Show a DataFrame as an HTML table with "Table n." and the caption above.

        Parameters
        ----------
        df : pandas.DataFrame
            What the page shows: keep it narrow (a few columns, intervals as
            one column with :func:`lsbg.tables.style.with_interval`) and short.
        caption : str
        formats : dict, optional
            ``{column: format string or callable}``; other numbers get
            ``digits`` significant figures.
        index : bool, default False
            Show the index.
        digits : int, default 4
        headers : dict, optional
            Column headers, over :data:`lsbg.tables.style.COLUMN_HEADERS`.
        full : pandas.DataFrame, optional
            The complete table behind a shortened one: attached to the report
            as a CSV file (embedded, full precision) linked below the table.
        """
        from IPython.display import HTML

        self.tables += 1
        html = format_table(df, formats, index=index, digits=digits, headers=headers)
        if full is not None:
            html += _csv_link(full, f"{self.name}-table-{self.tables}.csv")
        self._display(HTML(f"<p><b>Table {self.tables}.</b> {_escape(caption)}</p>{html}"))


def _csv_link(df, filename):
    """A link that downloads ``df`` as a CSV file embedded in the page (no file beside it)."""
    import base64

    data = base64.b64encode(df.to_csv(index=False).encode("utf-8")).decode()
    return (f'<p><a class="lsbg-csv" download="{filename}" href="data:text/csv;base64,{data}">'
            f"The full table ({len(df)} rows × {len(df.columns)} columns) as CSV: "
            f"{filename}</a></p>")


def _img(png, caption, style):
    """An <img> element with the PNG embedded and the caption as alternative text."""
    import base64

    alt = _escape(_plain_text(caption)).replace('"', "&quot;")
    return (f'<img src="data:image/png;base64,{base64.b64encode(png).decode()}" '
            f'alt="{alt}" style="{style}"/>')


def _plain_text(text):
    """Markdown caption without emphasis marks, for alt text."""
    return str(text).replace("**", "").replace("`", "")


def _escape(text):
    import html

    return html.escape(str(text), quote=False)
