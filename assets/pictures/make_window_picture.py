"""Write assets/pictures/window.png, the README's picture of the window: the explorer as it
opens on the bundled sample, grabbed from the screen. Run it under a display (`xvfb-run -a`
works):

    xvfb-run -a .venv/bin/python assets/pictures/make_window_picture.py
"""

from __future__ import annotations

import io
import os
import sys
import tempfile
from pathlib import Path

os.environ["QT_API"] = "pyside6"

from PIL import Image
from PySide6.QtCore import QBuffer, QSettings, QTimer
from PySide6.QtGui import QPixmap
from PySide6.QtWidgets import QApplication

from app.main_window import MainWindow
from app.resources import SAMPLE_PATH

SIZE = (960, 600)
SETTLE_MS = 1500  # let the docks lay out and the first frame render after the build
TARGET = Path(__file__).resolve().parent / "window.png"


def save_small_png(pixmap: QPixmap, target: Path) -> None:
    """Save pixmap as a palette PNG (256 colours): a third of the size, no visible loss."""
    buffer = QBuffer()
    buffer.open(QBuffer.OpenModeFlag.WriteOnly)
    pixmap.save(buffer, "PNG")
    image = Image.open(io.BytesIO(buffer.data().data())).convert("RGB")
    image.quantize(colors=256).save(target, format="PNG", optimize=True)


def main() -> int:
    """Open the window on the sample with default settings, grab it once shown, and quit."""
    app = QApplication.instance() or QApplication(sys.argv[:1])
    with tempfile.TemporaryDirectory() as folder:
        settings = QSettings(str(Path(folder) / "settings.ini"), QSettings.Format.IniFormat)
        window = MainWindow(settings)
        window.resize(*SIZE)
        window.show()

        def grab() -> None:
            save_small_png(app.primaryScreen().grabWindow(window.winId()), TARGET)
            window.close()
            app.quit()

        window.model.datasetChanged.connect(lambda *_: QTimer.singleShot(SETTLE_MS, grab))
        window.open_path(SAMPLE_PATH)
        app.exec()
    print(f"wrote {TARGET}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
