(define (problem lander-04)
  (:domain lander)
  (:init
    (flying)
    (= (h) 641.1) (= (v) -20)
    (= (mass) 1105.12) (= (fuel) 105.12) (= (burn-rate) 5)
    (= (gravity) 1.62) (= (thrust) 4654.8)
    (= (touch-height) 2.5) (= (safe-speed) 2))
  (:goal (and (landed))))
