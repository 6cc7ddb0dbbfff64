"""laser_filters: LaserScan filter chains (scan_to_scan_filter_chain) configured as the filters library reads them."""
