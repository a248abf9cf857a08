from unsew.cli import main

raise SystemExit(main())
